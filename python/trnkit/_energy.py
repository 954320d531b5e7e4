"""trnkit.integrate_energy over the compiled primitive of trnkit._trnkit (python/src/py_energy.cpp)."""
from __future__ import annotations

import os
from collections.abc import Mapping

from . import _trnkit

__all__ = ["integrate_energy"]


def integrate_energy(log: str | os.PathLike, markers: str | os.PathLike, *, format: str = "auto",
                     options: Mapping[str, str] | None = None, align: str = "same-clock", offset: float = 0.0, search: float = 0.0,
                     insist: bool = False, clock: str = "real", rule: str = "trapezoid", min_samples: int = 3) -> dict:
    """Per-frame joules of a power log between the frame markers of `trnkit frames`, as
    `trnkit energy integrate` computes them (docs/ENERGY.md).

    format: "auto" or a log format name; options: its parser's {key: value}. align: "same-clock",
    "offset" (t_log = t_marker + offset seconds) or "auto" (within +-search s; insist accepts an
    ambiguous estimate). clock: the marker clock, "real" or "mono". rule: "trapezoid" or "hold";
    min_samples: fewer samples in a frame flag it unusable.

    Returns a dict of per-frame NumPy arrays id, start_s, end_s (s), gross_j, net_j (J above the
    idle baseline), error_j (the bound), samples, usable, and flag (list), with idle_w (W),
    offset_s, drift, align, platform and warnings.
    """
    return _trnkit.integrate_energy(os.fspath(log), os.fspath(markers), format, {str(k): str(v) for k, v in (options or {}).items()},
                                    align, float(offset), float(search), bool(insist), clock, rule, int(min_samples))
