# Type stubs of the trnkit package (shipped with it; tests/python/test_package.py checks that every
# public callable here has the runtime signature it states). Units: see the module docstring.
import os
from collections.abc import Iterable, Mapping
from contextlib import AbstractContextManager
from typing import Any, Literal, NamedTuple, TypedDict, overload

import numpy as np
import numpy.typing as npt

__version__: str
git_commit: str

TOO_FEW_SAMPLES: int
FLAT_PATCH: int
FLAT_TEMPLATE: int
# (ncc, cc, ssd: float32; valid_samples, flags: uint32)
SCORE_DTYPE: np.dtype[np.void]

class Error(ValueError, RuntimeError): ...
class BackendUnavailable(Error): ...
class YawUnitWarning(UserWarning): ...

class PhaseTimes(NamedTuple):
    upload_ms: float
    execute_ms: float
    download_ms: float
    @property
    def total_ms(self) -> float: ...

class Sampling:
    @property
    def kind(self) -> Literal["dense", "random", "explicit"]: ...
    @staticmethod
    def dense() -> Sampling: ...
    @staticmethod
    def random(fraction: float, seed: int = 1) -> Sampling: ...
    @staticmethod
    def explicit(points: npt.ArrayLike) -> Sampling: ...

class Plan:
    @property
    def sample_count(self) -> int: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...

class Map:
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def backend(self) -> str: ...

class Backend:
    def __init__(self, spec: str, *, threads: int = 0, simd: bool = True, opencl_device: int | str | None = None,
                 vulkan_device: int | str | None = None, work_group: int = 0, cache_dir: str | os.PathLike[str] | None = None,
                 particles_per_group: int = 0, quad_maps: bool = True, subgroups: bool = True, force_staging: bool = False,
                 validation: bool = False) -> None: ...
    @property
    def name(self) -> str: ...
    @property
    def info(self) -> dict[str, str]: ...
    @property
    def closed(self) -> bool: ...
    @overload
    def upload_map(self, map: npt.NDArray[np.uint8], *, valid: npt.NDArray[np.uint8] | None = None,
                   return_times: Literal[False] = False) -> Map: ...
    @overload
    def upload_map(self, map: npt.NDArray[np.uint8], *, valid: npt.NDArray[np.uint8] | None = None,
                   return_times: Literal[True]) -> tuple[Map, PhaseTimes]: ...
    @overload
    def score(self, map: Map, template: npt.NDArray[Any] | Plan, poses: npt.ArrayLike, sampling: Sampling | None = None,
              min_valid_fraction: float = 0.9, *, out: npt.NDArray[np.void] | None = None,
              return_times: Literal[False] = False) -> npt.NDArray[np.void]: ...
    @overload
    def score(self, map: Map, template: npt.NDArray[Any] | Plan, poses: npt.ArrayLike, sampling: Sampling | None = None,
              min_valid_fraction: float = 0.9, *, out: npt.NDArray[np.void] | None = None,
              return_times: Literal[True]) -> tuple[npt.NDArray[np.void], PhaseTimes]: ...
    @overload
    def sobel(self, image: npt.NDArray[np.uint8], *,
              return_times: Literal[False] = False) -> tuple[npt.NDArray[np.int16], npt.NDArray[np.int16]]: ...
    @overload
    def sobel(self, image: npt.NDArray[np.uint8], *,
              return_times: Literal[True]) -> tuple[npt.NDArray[np.int16], npt.NDArray[np.int16], PhaseTimes]: ...
    def close(self) -> None: ...
    def __enter__(self) -> Backend: ...
    def __exit__(self, *exc: object) -> None: ...

def devices() -> list[dict[str, str]]: ...
def families() -> list[str]: ...
def plan(template: npt.NDArray[Any], sampling: Sampling | None = None, min_valid_fraction: float = 0.9) -> Plan: ...

class PowerTrace:
    source: str
    format: str
    quantity: str
    wall_clock: bool
    notes: list[str]
    warnings: list[str]
    @property
    def kind(self) -> Literal["instant", "interval-mean"]: ...
    @property
    def t(self) -> npt.NDArray[np.float64]: ...
    @property
    def w(self) -> npt.NDArray[np.float64]: ...
    def __len__(self) -> int: ...
    def save(self, path: str | os.PathLike[str]) -> None: ...

def power_sources(*, sysfs_root: str | os.PathLike[str] = "/sys", nvml_library: str = "libnvidia-ml.so.1",
                  vcgencmd: str | os.PathLike[str] = "/usr/bin/vcgencmd") -> list[str]: ...

class PowerSampler:
    period_s: float
    clock: Literal["real", "mono"]
    trace: PowerTrace | None
    def __init__(self, source: str, *, period_s: float = 0.01, clock: Literal["real", "mono"] = "real",
                 sysfs_root: str | os.PathLike[str] = "/sys", nvml_library: str = "libnvidia-ml.so.1",
                 vcgencmd: str | os.PathLike[str] = "/usr/bin/vcgencmd") -> None: ...
    @property
    def description(self) -> str: ...
    @property
    def running(self) -> bool: ...
    @property
    def late_polls(self) -> int: ...
    def start(self) -> PowerSampler: ...
    def stop(self) -> PowerTrace: ...
    def sample(self, duration_s: float) -> PowerTrace: ...
    def __enter__(self) -> PowerSampler: ...
    def __exit__(self, *exc: object) -> None: ...

class MeasurementWindows:
    def __init__(self, meta: Mapping[str, str] | None = None) -> None: ...
    def begin_frame(self) -> int: ...
    def end_frame(self, write_ms: float = 0.0, exec_ms: float = 0.0, read_ms: float = 0.0) -> None: ...
    def frame(self) -> AbstractContextManager[int]: ...
    def begin_idle(self) -> None: ...
    def end_idle(self) -> None: ...
    def idle_for(self, seconds: float) -> None: ...
    @property
    def open(self) -> bool: ...
    @property
    def frames(self) -> int: ...
    def rows(self) -> list[tuple[str, int, int, int, int, int]]: ...
    def save(self, path: str | os.PathLike[str]) -> None: ...
    def save_minimal(self, path: str | os.PathLike[str], realtime: bool = True) -> None: ...

def integrate_energy(log: str | os.PathLike[str] | PowerTrace, markers: str | os.PathLike[str] | MeasurementWindows | None, *,
                     format: str = "auto", options: Mapping[str, str] | None = None,
                     align: Literal["same-clock", "offset", "auto"] = "same-clock", offset: float = 0.0, search: float = 0.0,
                     insist: bool = False, clock: Literal["real", "mono"] | None = None,
                     rule: Literal["trapezoid", "hold"] = "trapezoid", min_samples: int = 3) -> dict[str, Any]: ...

# --- localization (trn::localize): map pixels, RADIANS, metres -----------------------------------

class Estimate(TypedDict):  # what Localizer.step returns (a dict at run time; test_localize checks the keys)
    x: float
    y: float
    yaw: float
    best_x: float
    best_y: float
    best_yaw: float
    best_ncc: float
    spread_m: float
    particles: int
    off_map: int
    frame_missing: bool
    too_oblique: bool
    tilt_deg: float
    odometry_lost: bool
    reinitialised: bool
    odometry_source: Literal["given", "none", "visual:start", "visual:features", "visual:phase", "visual:lost", "visual:no-frame"]
    lock_state: Literal["none", "unknown", "ok", "weak", "inconsistent", "fix", "lost"]
    lock_contrast: float
    lock_drift_m: float
    score_ms: float
    step_ms: float
    yaw_sd: float
    cov_xx_px2: float
    cov_xy_px2: float
    cov_yy_px2: float
    cov_nn_m2: float
    cov_ne_m2: float
    cov_ee_m2: float
    eph_m: float
    latitude_deg: float | None
    longitude_deg: float | None
    time_s: float | None
    vel_north_mps: float | None
    vel_east_mps: float | None
    vel_var_m2ps2: float | None

class Localizer(AbstractContextManager["Localizer"]):
    def __init__(self, map: npt.NDArray[np.uint8], metres_per_pixel: float, backend: Backend | str = "fastest", *,
                 valid: npt.NDArray[np.uint8] | None = None, start: tuple[float, float],
                 start_heading_rad: float | None = None, camera_hfov_deg: float | None = None, max_tilt_deg: float = 10.0,
                 template_width: int = 160, sparse: float = 1.0, seed: int = 1, conversion: str = "logistic:0.2",
                 sampling: Literal["kld", "importance", "rejection"] = "kld", min_particles: int | None = None,
                 max_particles: int | None = None, particles: int | None = None, init_radius_m: float | None = None,
                 reinit_radius_m: float | None = None, heading: Literal["compass", "none"] = "compass",
                 start_heading_sd_deg: float | None = None, profile: Literal["ours", "dissertation"] = "ours",
                 lock_monitor: bool | None = None, map_origin: tuple[float, float] | None = None,
                 compassless_max_particles: int | None = None, visual_odometry: bool = False) -> None: ...
    def step(self, frame: npt.NDArray[np.uint8] | None = None, *, odometry: tuple[float, float] | None = None,
             heading_rad: float | None = None, altitude_agl_m: float | None = None, scale: float | None = None,
             attitude: tuple[float, float] | None = None, odometry_yaw_rad: float | None = None,
             time_s: float | None = None) -> Estimate: ...
    def reanchor(self, position: tuple[float, float], *, radius_m: float, heading_rad: float | None = None) -> None: ...
    def close(self) -> None: ...

def load_map(path: str | os.PathLike[str], nodata: int | None = None) -> tuple[npt.NDArray[np.uint8], npt.NDArray[np.uint8] | None]: ...
def load_gray(path: str | os.PathLike[str]) -> npt.NDArray[np.uint8]: ...
def load_validity(path: str | os.PathLike[str], nodata: int | None = None) -> npt.NDArray[np.uint8] | None: ...
def read_air_folder(folder: str | os.PathLike[str]) -> list[dict[str, Any]]: ...
def localizer_defaults(profile: Literal["ours", "dissertation"] = "ours",
                       heading: Literal["compass", "none"] = "compass") -> dict[str, Any]: ...
def localize(*, dataset: str, map: str = "", backend: Backend | str = "fastest", metres_per_pixel: float = 0.0, hfov_deg: float = 0.0,
             fps: float = 0.0, rate_hz: float = 5.0, start: tuple[float, float] | None = None, start_heading_rad: float | None = None,
             odometry: Literal["recorded", "visual"] = "recorded", max_tilt_deg: float = 10.0, template_width: int = 160,
             sparse: float = 1.0, seed: int = 1, conversion: str = "logistic:0.2", sampling: str = "kld",
             min_particles: int | None = None, max_particles: int | None = None, particles: int | None = None,
             init_radius_m: float | None = None, reinit_radius_m: float | None = None,
             out: str = "", plots: bool = False, heading: Literal["compass", "none"] = "compass",
             start_heading_sd_deg: float | None = None, nodata: int | None = None,
             profile: Literal["ours", "dissertation"] = "ours", lock_monitor: bool | None = None,
             compassless_max_particles: int | None = None) -> dict[str, Any]: ...

class MavlinkEncoder:
    def __init__(self, *, system_id: int = 1, component_id: int = 197,
                 messages: str | Iterable[Literal["gps_input", "global_position", "odometry"]] = ("gps_input", "global_position", "odometry"),
                 sensor_id: int = 0, satellites: int = 10) -> None: ...
    def encode(self, *, time_us: int, valid: bool, reset: bool = False, lat_deg: float = ..., lon_deg: float = ...,
               alt_msl_m: float = ..., north_m: float = ..., east_m: float = ..., cov_nn: float = ..., cov_ne: float = ...,
               cov_ee: float = ..., spread_m: float = ..., vel_north: float = ..., vel_east: float = ..., vel_var: float = ...,
               yaw_rad: float = ..., yaw_var: float = ..., processing_us: int = 0) -> bytes: ...
