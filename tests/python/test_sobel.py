"""Backend.sobel against a NumPy Sobel (reflect-101 borders, the cv::Sobel(CV_16S) result)."""
import numpy as np

from conftest import texture


def numpy_sobel(img):
    p = np.pad(img.astype(np.int32), 1, mode="reflect")  # numpy's "reflect" is OpenCV's reflect-101
    h, w = img.shape
    s = lambda dy, dx: p[1 + dy:1 + dy + h, 1 + dx:1 + dx + w]
    gx = (s(-1, 1) - s(-1, -1)) + 2 * (s(0, 1) - s(0, -1)) + (s(1, 1) - s(1, -1))
    gy = (s(1, -1) - s(-1, -1)) + 2 * (s(1, 0) - s(-1, 0)) + (s(1, 1) - s(-1, 1))
    return gx.astype(np.int16), gy.astype(np.int16)


def test_sobel_matches_numpy(backend):
    img = texture(57, 83, seed=4)
    img[10:20, 30:40] = 255  # hard edges
    gx, gy = backend.sobel(img)
    assert gx.dtype == np.int16 and gx.shape == img.shape and gy.shape == img.shape
    wx, wy = numpy_sobel(img)
    np.testing.assert_array_equal(gx, wx)
    np.testing.assert_array_equal(gy, wy)


def test_sobel_of_a_strided_view(backend):
    big = texture(64, 100, seed=6)
    view = big[3:50, 7:90]  # row stride 100, read in place
    wx, wy = numpy_sobel(np.ascontiguousarray(view))
    gx, gy = backend.sobel(view)
    np.testing.assert_array_equal(gx, wx)
    np.testing.assert_array_equal(gy, wy)
