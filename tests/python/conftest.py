"""Shared helpers of the trnkit Python tests (run from ctest: PYTHONPATH holds the built module,
TRNKIT_EXE the CLI, TRN_REQUIRE_BACKENDS the families whose absence is a failure)."""
import os

import numpy as np
import pytest

import trnkit

ALL_FAMILIES = ["cpu-ref", "cpu", "opencl", "vulkan"]


def required_families():
    return [f for f in os.environ.get("TRN_REQUIRE_BACKENDS", "").replace(",", ";").split(";") if f]


def backend_or_skip(family):
    """The backend of a family; a family without devices skips (or fails when it is required)."""
    try:
        return trnkit.Backend(family)
    except trnkit.BackendUnavailable as e:
        if family in required_families():
            pytest.fail(f"{family} is required (TRN_REQUIRE_BACKENDS) but NOT AVAILABLE: {e}")
        pytest.skip(f"{family} NOT AVAILABLE: {e}")


@pytest.fixture(params=ALL_FAMILIES)
def backend(request):
    return backend_or_skip(request.param)


def texture(height, width, seed=1):
    """A smooth random texture (NCC needs structure): sums of random sinusoids plus a little noise."""
    rng = np.random.default_rng(seed)
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    img = np.zeros((height, width))
    for _ in range(6):
        fx, fy, ph = rng.uniform(0.01, 0.2), rng.uniform(0.01, 0.2), rng.uniform(0, 6.3)
        img += np.sin(fx * x + fy * y + ph)
    img = 128 + 20 * img + rng.normal(0, 4, (height, width))
    return np.clip(img, 0, 255).astype(np.uint8)


def write_pgm(path, image):
    """A binary PGM (P5) that OpenCV, and so the trnkit CLI, reads."""
    h, w = image.shape
    with open(path, "wb") as f:
        f.write(b"P5\n%d %d\n255\n" % (w, h))
        f.write(np.ascontiguousarray(image, dtype=np.uint8).tobytes())


def trnkit_exe():
    exe = os.environ.get("TRNKIT_EXE")
    assert exe and os.path.exists(exe), "TRNKIT_EXE must name the trnkit CLI (set by ctest)"
    return exe
