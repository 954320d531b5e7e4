"""Energy from Python: live power sources (PowerSampler), measurement windows around your own calls
(MeasurementWindows) and the integration step (integrate_energy), over the compiled primitives of
trnkit._trnkit (python/src/py_energy.cpp). docs/ENERGY.md has the method and its error bound.

    sampler = trnkit.PowerSampler("rapl:package-0", period_s=0.005)
    windows = trnkit.MeasurementWindows()
    with sampler:                           # polls on a thread from here ...
        windows.idle_for(0.5)               # the idle baseline subtracted from every frame
        for batch in batches:
            with windows.frame():           # one window per call
                backend.score(m, template, batch)
        windows.idle_for(0.5)
    report = trnkit.integrate_energy(sampler.trace, windows)   # ... to here
    report["net_j"]                         # joules above idle of each score call
"""
from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator, Mapping

from . import _trnkit
from ._trnkit import PowerTrace

__all__ = ["MeasurementWindows", "PowerSampler", "PowerTrace", "integrate_energy", "power_sources"]

_NVML = "libnvidia-ml.so.1"
_VCGENCMD = "/usr/bin/vcgencmd"


def _options(sysfs_root, nvml_library, vcgencmd=_VCGENCMD) -> _trnkit.SamplerOptions:
    return _trnkit.SamplerOptions(os.fspath(sysfs_root), os.fspath(nvml_library), os.fspath(vcgencmd))


def _clock(clock: str, keyword: str = "clock") -> str:
    if clock not in ("real", "mono"):
        raise ValueError(f"{keyword} {clock!r}: expected 'real' (CLOCK_REALTIME, UNIX seconds) or 'mono' (CLOCK_MONOTONIC)")
    return clock


def power_sources(*, sysfs_root: str | os.PathLike = "/sys", nvml_library: str = _NVML,
                  vcgencmd: str | os.PathLike = _VCGENCMD) -> list[str]:
    """One line per live power source PowerSampler can open on this machine (hwmon INA2xx/INA3221
    rails, RAPL zones, NVIDIA GPUs), plus a line saying why NVML is not available when it is not."""
    return _trnkit.power_sources(_options(sysfs_root, nvml_library, vcgencmd))


class PowerSampler:
    """A live power source, polled every period_s seconds on a background thread while yours works.

    source: "hwmon:NAME[:CHANNEL]" (an INA2xx/INA3221 under SYSFS/class/hwmon), "rapl:NAME"
    (powercap energy counter), "nvml:INDEX[:power|:energy]" (an NVIDIA board) or "pmic:vcgencmd"
    (a Raspberry Pi 5's PMIC rails, read by running vcgencmd pmic_read_adc at every poll);
    power_sources() lists them. Opening checks the source (trnkit.Error naming it and why).
    period_s: seconds between polls (> 0). clock: "real" (CLOCK_REALTIME: UNIX seconds, the clock
    MeasurementWindows and other loggers share) or "mono" (CLOCK_MONOTONIC).
    sysfs_root, nvml_library, vcgencmd: where to look (tests point them at a fake tree, library or
    program; vcgencmd is an absolute path, run with an empty environment).

    start() polls once at once (a source that cannot be read fails before any work) and starts the
    thread; stop() polls once more and returns the PowerTrace (t in seconds on `clock`, w in
    watts). As a context manager it starts on entry and stops on exit; the trace is then .trace.
    """

    def __init__(self, source: str, *, period_s: float = 0.01, clock: str = "real", sysfs_root: str | os.PathLike = "/sys",
                 nvml_library: str = _NVML, vcgencmd: str | os.PathLike = _VCGENCMD) -> None:
        if not isinstance(source, str):
            raise TypeError(f"source must be a str such as 'rapl:package-0', not {type(source).__name__}")
        period_s = float(period_s)
        if not period_s > 0:
            raise ValueError(f"period_s={period_s}: expected seconds > 0")
        self.period_s, self.clock = period_s, _clock(clock)
        self._s = _trnkit.PowerSampler(source, _options(sysfs_root, nvml_library, vcgencmd))
        self.trace: PowerTrace | None = None

    @property
    def description(self) -> str:
        """The source and where it was found: "hwmon:ina3221:2 (/sys/class/hwmon/hwmon3)"."""
        return self._s.description

    @property
    def running(self) -> bool:
        return self._s.running

    @property
    def late_polls(self) -> int:
        """Polls (so far) that came more than one period after their due time (a loaded machine)."""
        return self._s.late_polls

    def start(self) -> PowerSampler:
        """Polls once and starts the sampler thread; trnkit.Error when already running or the read fails."""
        self._s._start(self.period_s, self.clock)
        self.trace = None
        return self

    def stop(self) -> PowerTrace:
        """Polls once more, stops the thread and returns (and keeps as .trace) every sample since
        start(); re-raises an error the thread hit, naming the source."""
        self.trace = self._s._stop()
        return self.trace

    def sample(self, duration_s: float) -> PowerTrace:
        """Polls every period_s for duration_s seconds on this thread (the first poll at once) and
        returns the trace; the sampler must not be running."""
        return self._s._sample(self.period_s, float(duration_s), self.clock)

    def __enter__(self) -> PowerSampler:
        return self.start()

    def __exit__(self, *exc) -> None:
        if self._s.running:
            self.stop()

    def __repr__(self) -> str:
        return f"<trnkit.PowerSampler {self.description}, every {self.period_s:g} s{', running' if self.running else ''}>"


class MeasurementWindows:
    """Marks where each frame of your work starts and ends, and where the program idles (the
    baseline integrate_energy subtracts), on CLOCK_MONOTONIC and CLOCK_REALTIME at once.

    meta: key=value pairs for the marker header (backend, kernel, ...). Frames are numbered 0, 1, ...
    in order; windows never overlap (opening one while another is open raises trnkit.Error).
    integrate_energy(trace, windows) gives joules per frame; save() writes the marker file that
    `trnkit energy integrate LOG --markers FILE` reads, for a power log of any other logger.
    """

    def __init__(self, meta: Mapping[str, str] | None = None) -> None:
        self._w = _trnkit.MeasurementWindows({str(k): str(v) for k, v in (meta or {}).items()})

    def begin_frame(self) -> int:
        """Opens the next frame and returns its id."""
        return self._w._begin_frame()

    def end_frame(self, write_ms: float = 0.0, exec_ms: float = 0.0, read_ms: float = 0.0) -> None:
        """Closes the open frame; the phase times (ms) are optional, e.g. from return_times=True."""
        self._w._end_frame(float(write_ms), float(exec_ms), float(read_ms))

    @contextlib.contextmanager
    def frame(self) -> Iterator[int]:
        """`with windows.frame() as id:` one frame around the block (ended by an exception too)."""
        frame_id = self.begin_frame()
        try:
            yield frame_id
        finally:
            self.end_frame()

    def begin_idle(self) -> None:
        """Opens an idle window (around a wait of your program's own)."""
        self._w._begin_idle()

    def end_idle(self) -> None:
        self._w._end_idle()

    def idle_for(self, seconds: float) -> None:
        """An idle window of `seconds`: sleeps (without the GIL)."""
        self._w._idle_for(float(seconds))

    @property
    def open(self) -> bool:
        """A frame or idle window is open."""
        return self._w.open

    @property
    def frames(self) -> int:
        """Frames opened so far."""
        return self._w.frames

    def rows(self) -> list[tuple[str, int, int, int, int, int]]:
        """The closed windows: (kind, id, mono_start_ns, mono_end_ns, real_start_ns, real_end_ns)."""
        return self._w._rows()

    def save(self, path: str | os.PathLike) -> None:
        """Writes the closed windows in the trnkit-frames format, whole (temporary name, then rename)."""
        self._w._save(os.fspath(path))

    def save_minimal(self, path: str | os.PathLike, realtime: bool = True) -> None:
        """Writes the frames as `frame,start_s,end_s` in UNIX (realtime) or CLOCK_MONOTONIC seconds."""
        self._w._save_minimal(os.fspath(path), bool(realtime))


def integrate_energy(log: str | os.PathLike | PowerTrace, markers: str | os.PathLike | MeasurementWindows | None, *,
                     format: str = "auto", options: Mapping[str, str] | None = None, align: str = "same-clock",
                     offset: float = 0.0, search: float = 0.0, insist: bool = False, clock: str | None = None,
                     rule: str = "trapezoid", min_samples: int = 3) -> dict:
    """Per-frame joules of a power log between frame markers, as `trnkit energy integrate` computes them.

    log: a power log file (format "auto" or a name from docs/ENERGY.md; options: its parser's
    {key: value}) or a PowerTrace (PowerSampler.stop()). markers: a marker file (`trnkit frames`,
    MeasurementWindows.save, or the minimal frame,start_s,end_s), a MeasurementWindows, or None for
    the log's own start/end markers (PMT). align: "same-clock" (log and markers share a clock),
    "offset" (t_log = t_marker + offset seconds) or "auto" (offset and drift from the busy/idle
    pattern, within +-search s of offset; insist accepts an ambiguous estimate). clock: the marker
    clock, "real" or "mono"; None = the trace's clock for a PowerTrace, else "real". rule:
    "trapezoid" or "hold"; min_samples: fewer samples in a frame flag it unusable.

    Returns a dict of per-frame NumPy arrays id, start_s, end_s (seconds on the log's clock),
    gross_j, net_j (J above the idle baseline), error_j (the bound), samples, usable, marker_ms,
    write_ms, exec_ms, read_ms, and flag (list of str, "" when usable), with idle_w (W), offset_s,
    drift, align, platform and warnings.
    """
    if isinstance(log, PowerTrace):
        log_arg = log
        if clock is None:
            clock = "real" if log.wall_clock else "mono"
    elif isinstance(log, (str, os.PathLike)):
        log_arg = os.fspath(log)
    else:
        raise TypeError(f"log must be a path or a trnkit.PowerTrace, not {type(log).__name__}")
    if markers is None:
        markers_arg = ""
    elif isinstance(markers, MeasurementWindows):
        markers_arg = markers._w
    elif isinstance(markers, (str, os.PathLike)):
        markers_arg = os.fspath(markers)
    else:
        raise TypeError(f"markers must be a path, a trnkit.MeasurementWindows or None, not {type(markers).__name__}")
    return _trnkit.integrate_energy(log_arg, markers_arg, format, {str(k): str(v) for k, v in (options or {}).items()}, align,
                                    float(offset), float(search), bool(insist), clock or "real", rule, int(min_samples))


def _save_trace(self: PowerTrace, path: str | os.PathLike) -> None:
    """Writes the trace as a trnkit-power log (`trnkit energy integrate` reads it), whole."""
    self._save(os.fspath(path))


_save_trace.__name__ = "save"
PowerTrace.save = _save_trace
