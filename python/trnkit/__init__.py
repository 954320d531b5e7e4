"""trnkit: batched particle scoring (NCC, CC, SSD) of poses against an orthophoto map, Sobel, the
DPC-PFL localizer (Localizer, localize, read_air_folder), its estimates as MAVLink v2 for an
autopilot (MavlinkEncoder) and energy measurement, on the cpu-ref, cpu, OpenCL and Vulkan backends
(docs/EMBEDDING.md).

Conventions (trn/scoring.hpp):
  * Images are 2-D NumPy arrays (height, width); a map is uint8 grey levels, a template uint8 or
    float. Map pixel centres are at integer coordinates: x = column, y = row.
  * A pose is one row (x, y, yaw, scale) of an (N, 4) array: the map pixel of the template centre
    ((W-1)/2, (H-1)/2), the heading in RADIANS (positive turns the template clockwise on screen)
    and the map pixels per template pixel.
  * Scores are a structured array of SCORE_DTYPE (ncc, cc, ssd, valid_samples, flags); a particle
    with flags != 0 (TOO_FEW_SAMPLES | FLAT_PATCH | FLAT_TEMPLATE) is invalid and scores 0.
  * Times are milliseconds (PhaseTimes) or seconds (energy); energy is joules, power watts.

Errors: trnkit.Error (a ValueError and a RuntimeError) carries the library's message naming the
argument, keyword, file or device; trnkit.BackendUnavailable (an Error) for a backend this build or
machine does not have. Wrong array types and shapes raise TypeError / ValueError naming the argument.
"""
import numpy  # noqa: F401  (first: a missing NumPy is named, not "initialization failed")

from ._trnkit import (FLAT_PATCH, FLAT_TEMPLATE, SCORE_DTYPE, TOO_FEW_SAMPLES, BackendUnavailable, Error, Map, Plan,
                      Sampling, __version__, git_commit)
from ._backend import Backend, PhaseTimes, YawUnitWarning, devices, families, plan
from ._energy import MeasurementWindows, PowerSampler, PowerTrace, integrate_energy, power_sources
from ._localize import Localizer, load_gray, load_map, load_validity, localize, localizer_defaults, read_air_folder
from ._mavlink import MavlinkEncoder

__all__ = [
    "Backend", "BackendUnavailable", "Error", "FLAT_PATCH", "FLAT_TEMPLATE", "Localizer", "Map", "MavlinkEncoder", "MeasurementWindows",
    "PhaseTimes",
    "Plan", "PowerSampler", "PowerTrace", "SCORE_DTYPE", "Sampling", "TOO_FEW_SAMPLES", "YawUnitWarning", "devices",
    "families", "git_commit", "integrate_energy", "load_gray", "load_map", "load_validity", "localize", "localizer_defaults", "plan", "power_sources", "read_air_folder",
]

# Every public class says it is trnkit's (repr, help, pickle), not trnkit._trnkit's or trnkit._backend's.
for _cls in (Backend, Localizer, Map, MavlinkEncoder, MeasurementWindows, PhaseTimes, Plan, PowerSampler, PowerTrace, Sampling, YawUnitWarning):
    _cls.__module__ = __name__
del _cls
