"""Bad input raises a clear Python exception carrying trnkit's message."""
import numpy as np
import pytest

import trnkit
from conftest import texture

MAP = texture(64, 80)


def test_exception_classes():
    assert issubclass(trnkit.Error, ValueError) and issubclass(trnkit.Error, RuntimeError)
    assert issubclass(trnkit.BackendUnavailable, trnkit.Error)


def test_bad_backend_spec():
    with pytest.raises(trnkit.BackendUnavailable, match="backend 'warp-drive' is not built into this trnkit"):
        trnkit.Backend("warp-drive")
    with pytest.raises(trnkit.BackendUnavailable, match="cpu:9"):
        trnkit.Backend("cpu:9")
    with pytest.raises(TypeError):
        trnkit.Backend(None)


def test_bad_images():
    b = trnkit.Backend("cpu")
    with pytest.raises(ValueError, match="map must have dtype uint8, not float64"):
        b.upload_map(MAP.astype(np.float64))
    with pytest.raises(ValueError, match=r"map must be 2-D \(height, width\), not of shape \(64, 80, 3\)"):
        b.upload_map(np.zeros((64, 80, 3), np.uint8))
    with pytest.raises(ValueError, match=r"map of shape \(0, 5\) is empty"):
        b.upload_map(np.zeros((0, 5), np.uint8))
    with pytest.raises(TypeError, match="map must be a numpy array, not list"):
        b.upload_map([[1, 2], [3, 4]])
    with pytest.raises(trnkit.Error, match="upload_map: map 1x1 is smaller than 2x2"):
        b.upload_map(np.zeros((1, 1), np.uint8))
    with pytest.raises(ValueError, match="image must have dtype uint8"):
        b.sobel(MAP.astype(np.int16))
    with pytest.raises(ValueError, match="template must have dtype uint8 or a float type, not int32"):
        b.score(b.upload_map(MAP), MAP[:8, :8].astype(np.int32), np.zeros((1, 4)))


def test_bad_scoring_arguments():
    b, other = trnkit.Backend("cpu"), trnkit.Backend("cpu-ref")
    m = b.upload_map(MAP)
    t = MAP[10:30, 10:30]
    ok = np.array([[40, 30, 0, 1]], np.float32)
    with pytest.raises(ValueError, match=r"poses must have shape \(N, 4\).*got shape \(3,\)"):
        b.score(m, t, [1, 2, 3])
    with pytest.raises(TypeError, match="poses must be an array-like"):
        b.score(m, t, "north")
    with pytest.raises(trnkit.Error, match="pose 1 has scale 0"):
        b.score(m, t, [[40, 30, 0, 1], [40, 30, 0, 0]])
    with pytest.raises(trnkit.Error, match="pose 0 has a non-finite yaw"):
        b.score(m, t, [[40, 30, np.nan, 1]])
    with pytest.raises(trnkit.Error, match="the map was uploaded to another backend than cpu-ref"):
        other.score(m, t, ok)
    with pytest.raises(trnkit.Error, match="smaller than the template"):
        b.score(m, texture(70, 90), ok)
    with pytest.raises(trnkit.Error, match="0.0|fraction"):
        b.score(m, t, ok, sampling=trnkit.Sampling.random(0.0, 1))
    with pytest.raises(TypeError, match="sampling must be a trnkit.Sampling"):
        b.score(m, t, ok, sampling="dense")
    with pytest.raises(ValueError, match="sampling is part of the plan"):
        b.score(m, trnkit.plan(t), ok, sampling=trnkit.Sampling.dense())
    with pytest.raises(ValueError, match=r"shape \(K, 2\)"):
        trnkit.Sampling.explicit([1, 2, 3])
    with pytest.raises(trnkit.Error):
        trnkit.plan(t, trnkit.Sampling.explicit([[100, 100]]))


def test_map_keeps_its_backend_alive():
    b = trnkit.Backend("cpu")
    m = b.upload_map(MAP)
    del b
    import gc
    gc.collect()
    assert m.backend == "cpu" and m.width == 80
