"""trnkit.Backend and the scoring helpers: keyword checks, unit checks and docstrings over the
compiled primitives of trnkit._trnkit (python/src/py_backend.cpp)."""
from __future__ import annotations

import math
import os
import re
import warnings
from typing import NamedTuple

import numpy as np

from . import _trnkit
from ._trnkit import Error, Map, Plan, Sampling

__all__ = ["Backend", "PhaseTimes", "YawUnitWarning", "devices", "families", "plan"]

TWO_PI = 2 * math.pi


class YawUnitWarning(UserWarning):
    """Poses whose yaw looks like degrees: yaw is in radians (see Backend.score)."""


class PhaseTimes(NamedTuple):
    """Wall time of one call's phases in milliseconds, on the backend's own clock (OpenCL profiling
    events, Vulkan timestamp queries, steady_clock on the CPU): host-to-device copies, the kernels,
    device-to-host copies."""

    upload_ms: float
    execute_ms: float
    download_ms: float

    @property
    def total_ms(self) -> float:
        """upload_ms + execute_ms + download_ms."""
        return self.upload_ms + self.execute_ms + self.download_ms


def devices() -> list[dict[str, str]]:
    """Every usable device of every backend family this build has, as dicts with the keys name
    (what Backend takes: "cpu-ref", "cpu", "opencl:0", "vulkan:1"), family, device, type ("cpu",
    "gpu", "other"), driver and details. Families without devices are left out (`trnkit devices
    --verbose` says why)."""
    return _trnkit.devices()


def families() -> list[str]:
    """The backend families this trnkit lists ("cpu-ref", "cpu", "opencl", "vulkan", "cuda"; one the
    build lacks says so when created), whether or not this machine has devices for them."""
    return _trnkit.families()


def plan(template, sampling: Sampling | None = None, min_valid_fraction: float = 0.9) -> Plan:
    """Validates a template and its sampling once and prepares it for Backend.score (one plan per
    camera frame, scored for many batches of poses).

    template: 2-D array (height, width) of uint8 or float (float32 read in place, other floats
    converted). sampling: Sampling.dense() (None), .random(fraction, seed) or .explicit(points).
    min_valid_fraction: a particle whose in-map samples are fewer than this share of the plan's
    samples is flagged TOO_FEW_SAMPLES and scores 0."""
    return _trnkit.plan(template, sampling, float(min_valid_fraction))


def _dense() -> Sampling:
    """Every template pixel takes part in the score."""
    return Sampling._dense()


def _random(fraction: float, seed: int = 1) -> Sampling:
    """A share in (0, 1] of the template pixels, picked by `seed`: the same seed picks the same
    pixels on every backend."""
    return Sampling._random(float(fraction), _whole(seed, "seed", 0, 2**64 - 1))


def _explicit(points) -> Sampling:
    """These template pixels: an integer array of shape (K, 2) of (u, v) = (column, row)."""
    return Sampling._explicit(points)


_dense.__name__, _random.__name__, _explicit.__name__ = "dense", "random", "explicit"
Sampling.dense = staticmethod(_dense)
Sampling.random = staticmethod(_random)
Sampling.explicit = staticmethod(_explicit)


def _whole(value, keyword: str, lo: int, hi: int) -> int:
    """value as an int in [lo, hi]; TypeError or ValueError naming the keyword otherwise."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{keyword} must be an int, not {type(value).__name__}")
    value = int(value)
    if not lo <= value <= hi:
        raise ValueError(f"{keyword}={value}: expected {lo} to {hi}")
    return value


def _flag(value, keyword: str) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{keyword} must be True or False, not {type(value).__name__}")
    return bool(value)


def _device(value, keyword: str) -> str:
    """A device as after the colon of a spec: an index (int or digits) or a name text."""
    if value is None:
        return ""
    if isinstance(value, str):
        if not value:
            raise ValueError(f"{keyword}='': expected a device index or a name text (None: device 0)")
        return value
    return str(_whole(value, keyword, 0, 2**31 - 1))


def _folder(value, keyword: str) -> str:
    if value is None:
        return ""
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{keyword} must be a str or os.PathLike folder, not {type(value).__name__}")
    value = os.fspath(value)
    if not value:
        raise ValueError(f"{keyword}='': expected a folder (None: no disk cache)")
    return value


# Which families each keyword configures ("fastest" may pick any, so it takes them all).
_KEYWORD_FAMILIES = {
    "threads": ("cpu",), "simd": ("cpu",),
    "opencl_device": ("opencl",), "vulkan_device": ("vulkan",),
    "work_group": ("opencl", "vulkan"), "cache_dir": ("opencl", "vulkan"),
    "particles_per_group": ("vulkan",), "quad_maps": ("vulkan",), "subgroups": ("vulkan",),
    "force_staging": ("vulkan",), "validation": ("vulkan",),
}
# The library names BackendOptions fields in its messages; Python users know the keyword.
_FIELD_KEYWORDS = {
    "cpu.threads": "threads", "cpu.simd": "simd", "opencl.work_group": "work_group", "vulkan.work_group": "work_group",
    "opencl.program_cache_dir": "cache_dir", "vulkan.pipeline_cache_dir": "cache_dir",
    "vulkan.particles_per_group": "particles_per_group", "vulkan.quad_maps": "quad_maps", "vulkan.subgroups": "subgroups",
    "vulkan.force_staging": "force_staging", "vulkan.validation": "validation",
}


def _keyword_message(message: str) -> str:
    """The library's message with BackendOptions fields (and CLI variables) named as keywords."""
    message = re.sub(r" \(CLI: TRN_\w+\)", "", message)
    message = re.sub(r"BackendOptions\.(\w+\.\w+) = ", lambda m: _FIELD_KEYWORDS.get(m.group(1), m.group(0)) + "=", message)
    return re.sub(r"BackendOptions\.(\w+\.\w+)", lambda m: _FIELD_KEYWORDS.get(m.group(1), m.group(0)), message)


def _times(raw) -> PhaseTimes:
    return PhaseTimes(*raw)


class Backend(_trnkit.Backend):
    """One compute backend: scores particle poses against a camera frame on a map, and runs Sobel.

    spec: "cpu-ref" (the naive reference), "cpu" (optimized, threaded, AVX2), "opencl[:N|:name]",
    "vulkan[:N|:name]" (device by index or by a case-insensitive part of its name), or "fastest"
    (GPU OpenCL, GPU Vulkan, cpu, other devices, in that fixed order). A backend that is not
    available raises BackendUnavailable saying why; there is never a silent fallback.

    Keywords (every field of trn::BackendOptions; defaults are the tuned values). A keyword the
    spec's family does not have raises ValueError ("fastest" takes them all):
      threads: cpu worker threads, 0 = the hardware threads.
      simd: cpu, False = the portable inner loop even where AVX2 is available.
      opencl_device / vulkan_device: the device (index or name text) when the spec names only the
        family ("opencl"); None = device 0.
      work_group: scoring work-group size, a power of two (OpenCL; Vulkan at most 1024);
        0 = from the device's limits.
      cache_dir: folder for compiled OpenCL programs / the Vulkan pipeline cache; None = no disk
        cache (every new backend compiles its programs).
      particles_per_group: vulkan, 1 to 16 particles per work-group; 0 = from the device.
      quad_maps, subgroups, force_staging, validation: vulkan paths for tests (False = maps of one
        byte per pixel; the shared-memory reduction; staging buffers even with unified memory;
        True = the Khronos validation layer, whose messages fail the call).

    Calls on one backend run one at a time (a lock), without the GIL, so threads may share it.
    Backend is a context manager: leaving the `with` block (or close()) releases its maps and
    device memory; any later call raises trnkit.Error.
    """

    def __init__(self, spec: str, *, threads: int = 0, simd: bool = True, opencl_device: int | str | None = None,
                 vulkan_device: int | str | None = None, work_group: int = 0, cache_dir: str | os.PathLike | None = None,
                 particles_per_group: int = 0, quad_maps: bool = True, subgroups: bool = True, force_staging: bool = False,
                 validation: bool = False) -> None:
        if not isinstance(spec, str):
            raise TypeError(f"spec must be a str such as 'cpu', 'opencl:1' or 'fastest', not {type(spec).__name__}")
        given = {k: v for k, v in locals().items() if k in _KEYWORD_FAMILIES}
        family = spec.split(":", 1)[0]
        if family in ("cpu-ref", "cpu", "opencl", "vulkan", "cuda"):
            for keyword, value in given.items():
                default = Backend.__init__.__kwdefaults__[keyword]
                if family not in _KEYWORD_FAMILIES[keyword] and not (type(value) is type(default) and value == default):
                    raise ValueError(f"{keyword} is an option of {' and '.join(_KEYWORD_FAMILIES[keyword])} backends, "
                                     f"not of {spec!r}")
        wg_max = 1024 if family in ("vulkan", "fastest") else 65536
        work_group = _whole(work_group, "work_group", 0, 2**32 - 1)
        if work_group and (work_group & (work_group - 1) or work_group > wg_max):
            raise ValueError(f"work_group={work_group}: expected 0 (from the device) or a power of two up to {wg_max}")
        folder = _folder(cache_dir, "cache_dir")
        try:
            super().__init__(
                spec,
                threads=_whole(threads, "threads", 0, 2**31 - 1), simd=_flag(simd, "simd"),
                opencl_device=_device(opencl_device, "opencl_device"), vulkan_device=_device(vulkan_device, "vulkan_device"),
                opencl_work_group=work_group, vulkan_work_group=work_group, opencl_cache_dir=folder, vulkan_cache_dir=folder,
                particles_per_group=_whole(particles_per_group, "particles_per_group", 0, 16),
                quad_maps=_flag(quad_maps, "quad_maps"), subgroups=_flag(subgroups, "subgroups"),
                force_staging=_flag(force_staging, "force_staging"), validation=_flag(validation, "validation"))
        except Error as e:
            raise type(e)(_keyword_message(str(e))) from None

    def upload_map(self, map, *, valid=None, return_times: bool = False) -> Map:
        """Copies a map to the backend and returns its handle, to score many batches against.

        map: 2-D uint8 array (height, width), the orthophoto's grey levels; read in place when its
        rows are contiguous (any row stride, e.g. a slice of a larger array), else copied first.
        Map pixel centres are at integer coordinates (x = column, y = row). valid: the map's no-data,
        a 2-D uint8 array of the same shape, non-zero where a pixel is valid (trnkit.load_validity
        reads it from a file's alpha); a sample whose 2x2 bilinear cell touches an invalid pixel is
        left out of the scores like one off the map. None: every pixel valid. return_times=True
        returns (map, PhaseTimes)."""
        got = self._upload_map(map, valid, return_times)
        return (got[0], _times(got[1])) if return_times else got

    def score(self, map: Map, template, poses, sampling: Sampling | None = None, min_valid_fraction: float = 0.9, *,
              out: np.ndarray | None = None, return_times: bool = False) -> np.ndarray:
        """Scores every pose against the template on the map: NCC, CC and SSD per particle.

        map: from this backend's upload_map. template: a 2-D uint8/float array (height, width), or
        a Plan (trnkit.plan) built once per frame. poses: array-like of shape (N, 4), one row per
        particle: x, y = map pixel (column, row) of the template centre ((W-1)/2, (H-1)/2);
        yaw = heading in RADIANS (positive turns the template clockwise on screen); scale = map
        pixels per template pixel. A single pose must be shape (1, 4). When every |yaw| exceeds
        2 pi, or the yaws span more than two turns, they are probably degrees: YawUnitWarning
        (np.radians converts).
        sampling: Sampling.dense() (None), .random(fraction, seed), .explicit(points); with a Plan
        it is the plan's. min_valid_fraction: fewer in-map samples than this share flags the
        particle TOO_FEW_SAMPLES.

        Returns a structured array of N SCORE_DTYPE records (ncc, cc, ssd: float32; valid_samples,
        flags: uint32). flags != 0 (TOO_FEW_SAMPLES, FLAT_PATCH, FLAT_TEMPLATE bits) marks an
        invalid particle, whose scores are all 0 (never NaN). out: an array of SCORE_DTYPE and
        shape (N,) to write into (returned). return_times=True returns (scores, PhaseTimes)."""
        _check_yaw(poses)
        got = self._score(map, template, poses, sampling, float(min_valid_fraction), out, return_times)
        return (got[0], _times(got[1])) if return_times else got

    def sobel(self, image, *, return_times: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """3x3 Sobel of a 2-D uint8 image: (gx, gy) int16 arrays of its shape, bit-exact with
        cv::Sobel(image, CV_16S, 1, 0 / 0, 1, 3) with BORDER_REFLECT_101. return_times=True returns
        (gx, gy, PhaseTimes)."""
        got = self._sobel(image, return_times)
        return (got[0], got[1], _times(got[2])) if return_times else got

    def close(self) -> None:
        """Releases the backend's maps and device memory (waiting for a call in progress); later
        calls raise trnkit.Error. Calling it again does nothing."""
        self._close()

    def __enter__(self) -> Backend:
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __repr__(self) -> str:
        return f"trnkit.Backend({self.name!r}{', closed' if self.closed else ''})"


def _check_yaw(poses) -> None:
    """Warns (YawUnitWarning) when the yaw column looks like degrees."""
    a = poses if isinstance(poses, np.ndarray) else None
    if a is None and isinstance(poses, (list, tuple)):
        try:
            a = np.asarray(poses, dtype=np.float64)
        except (TypeError, ValueError):
            return  # the compiled check says what is wrong
    if a is None or a.ndim != 2 or a.shape[1] != 4 or a.shape[0] == 0 or a.dtype.kind not in "fiu":
        return
    yaw = np.abs(a[:, 2].astype(np.float64, copy=False))
    finite = yaw[np.isfinite(yaw)]
    if finite.size == 0:
        return
    if finite.min() > TWO_PI or (a[:, 2].max() - a[:, 2].min() > 2 * TWO_PI):
        warnings.warn(f"poses: yaw from {a[:, 2].min():g} to {a[:, 2].max():g}; yaw is in radians, these look like degrees "
                      "(np.radians converts; unwrapped radians: wrap them, or filter YawUnitWarning)", YawUnitWarning, stacklevel=3)
