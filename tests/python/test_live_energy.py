"""Live energy from Python: a PowerSampler thread on a fake hwmon rail, MeasurementWindows around
the caller's own work, and integrate_energy of the two giving joules per window; the marker file
they save reads back in `trnkit energy integrate`."""
import json
import os
import subprocess
import time

import numpy as np
import pytest

import trnkit
from conftest import texture, trnkit_exe

IDLE_W, BUSY_W = 2.0, 5.0


class FakeRail:
    """An INA226 under a fake sysfs root whose power1_input (uW) the test sets (written whole)."""

    def __init__(self, root):
        self.root = root
        self.chip = root / "class" / "hwmon" / "hwmon0"
        self.chip.mkdir(parents=True)
        (self.chip / "name").write_text("ina226\n")
        self.set(IDLE_W)

    def set(self, watts):
        tmp = self.chip / "power1_input.tmp"
        tmp.write_text(f"{int(watts * 1e6)}\n")
        os.replace(tmp, self.chip / "power1_input")


def busy(rail, seconds, work=None):
    """BUSY_W on the rail for `seconds` (running `work` meanwhile), then back to idle; returns how
    long the rail was busy (s)."""
    t0 = time.monotonic()
    rail.set(BUSY_W)
    if work:
        work()
    time.sleep(max(0.0, seconds - (time.monotonic() - t0)))
    rail.set(IDLE_W)
    return time.monotonic() - t0


def expect_joules(report, trace, busy_s):
    """net_j is (BUSY_W - IDLE_W) x the busy time, within what sampling can misplace: each edge by
    up to the longest interval between two polls (a loaded machine polls late)."""
    slack = (BUSY_W - IDLE_W) * 2 * np.diff(trace.t).max() + 0.01
    np.testing.assert_allclose(report["net_j"], (BUSY_W - IDLE_W) * np.asarray(busy_s), atol=slack)


def test_power_sources_lists_the_fake_rail(tmp_path):
    FakeRail(tmp_path)
    sources = trnkit.power_sources(sysfs_root=tmp_path, nvml_library="/no/such/libnvidia-ml.so")
    assert any("hwmon:ina226" in s for s in sources), sources
    s = trnkit.PowerSampler("hwmon:ina226", period_s=0.005, sysfs_root=tmp_path)
    assert "ina226" in s.description and not s.running
    trace = s.sample(0.05)
    assert len(trace) >= 5 and trace.wall_clock and np.all(trace.w == IDLE_W) and np.all(np.diff(trace.t) > 0)


def test_joules_per_score_call(tmp_path):
    rail = FakeRail(tmp_path)
    backend = trnkit.Backend("cpu")
    m = backend.upload_map(texture(300, 300))
    template = texture(300, 300)[100:140, 100:150]
    poses = np.column_stack([np.full(500, 150.0), np.full(500, 150.0), np.zeros(500), np.ones(500)])
    windows = trnkit.MeasurementWindows({"backend": backend.name, "kernel": "score"})
    durations, busy_s = [0.2, 0.3, 0.2], []
    with trnkit.PowerSampler("hwmon:ina226", period_s=0.002, sysfs_root=tmp_path) as sampler:
        assert sampler.running
        windows.idle_for(0.3)
        for i, seconds in enumerate(durations):
            with windows.frame() as frame_id:
                assert frame_id == i
                busy_s.append(busy(rail, seconds, lambda: backend.score(m, template, poses)))
            windows.idle_for(0.15)
        windows.idle_for(0.15)
    assert not sampler.running and len(sampler.trace) > 100
    assert windows.frames == 3 and not windows.open
    report = trnkit.integrate_energy(sampler.trace, windows)
    assert report["usable"].all(), report["flag"]
    assert report["idle_w"] == pytest.approx(IDLE_W, abs=0.05)
    # each window holds its busy time (a moment more: begin and end are marked around it)
    window_s = report["end_s"] - report["start_s"]
    assert np.all(window_s >= np.asarray(busy_s) - 1e-6) and np.all(window_s < np.asarray(busy_s) + 0.05)
    expect_joules(report, sampler.trace, busy_s)
    assert np.all(report["error_j"] >= 0) and report["id"].tolist() == [0, 1, 2]

    # The same windows and trace as files: the CLI's numbers.
    windows.save(tmp_path / "markers.csv")
    sampler.trace.save(tmp_path / "power.csv")
    cli = json.loads(subprocess.run([trnkit_exe(), "energy", "integrate", str(tmp_path / "power.csv"), "--markers",
                                     str(tmp_path / "markers.csv")], capture_output=True, text=True, check=True).stdout)
    np.testing.assert_allclose(report["net_j"], [f["net_j"] for f in cli["frames"]], rtol=1e-9, atol=1e-12)
    from_files = trnkit.integrate_energy(tmp_path / "power.csv", tmp_path / "markers.csv")
    np.testing.assert_allclose(from_files["net_j"], report["net_j"], rtol=1e-9, atol=1e-12)
    mixed = trnkit.integrate_energy(tmp_path / "power.csv", windows)
    np.testing.assert_allclose(mixed["net_j"], report["net_j"], rtol=1e-9, atol=1e-12)
    windows.save_minimal(tmp_path / "minimal.csv")
    assert "frame,start_s,end_s" in (tmp_path / "minimal.csv").read_text().splitlines()
    assert [r[0] for r in windows.rows()].count("frame") == 3


def test_monotonic_clock_and_phase_times(tmp_path):
    rail = FakeRail(tmp_path)
    windows = trnkit.MeasurementWindows()
    sampler = trnkit.PowerSampler("hwmon:ina226", period_s=0.002, clock="mono", sysfs_root=tmp_path).start()
    windows.idle_for(0.2)
    windows.begin_frame()
    busy_s = busy(rail, 0.2)
    windows.end_frame(write_ms=1.0, exec_ms=2.0, read_ms=3.0)
    windows.begin_idle()
    time.sleep(0.2)
    windows.end_idle()
    trace = sampler.stop()
    assert not trace.wall_clock
    report = trnkit.integrate_energy(trace, windows)  # clock from the trace: mono
    assert report["usable"].all() and report["exec_ms"].tolist() == [2.0] and report["read_ms"].tolist() == [3.0]
    expect_joules(report, trace, [busy_s])


def test_errors_name_the_source_and_the_mistake(tmp_path):
    rail = FakeRail(tmp_path)
    with pytest.raises(trnkit.Error, match="hwmon:ina999"):
        trnkit.PowerSampler("hwmon:ina999", sysfs_root=tmp_path)
    with pytest.raises(ValueError, match="period_s=0.0"):
        trnkit.PowerSampler("hwmon:ina226", period_s=0, sysfs_root=tmp_path)
    with pytest.raises(ValueError, match="clock 'utc'"):
        trnkit.PowerSampler("hwmon:ina226", clock="utc", sysfs_root=tmp_path)
    s = trnkit.PowerSampler("hwmon:ina226", sysfs_root=tmp_path)
    with pytest.raises(trnkit.Error, match="not running"):
        s.stop()
    with s:
        with pytest.raises(trnkit.Error, match="already running"):
            s.start()
        with pytest.raises(trnkit.Error, match="running"):
            s.sample(0.01)
    s.start()
    (rail.chip / "power1_input").write_text("garbage\n")
    time.sleep(0.05)
    with pytest.raises(trnkit.Error, match="power1_input"):
        s.stop()
    w = trnkit.MeasurementWindows()
    w.begin_frame()
    with pytest.raises(trnkit.Error, match="open"):
        w.begin_frame()
    with pytest.raises(trnkit.Error, match="still open"):
        trnkit.integrate_energy(tmp_path / "none.csv", w)
    with pytest.raises(TypeError, match="markers must be"):
        trnkit.integrate_energy(tmp_path / "none.csv", 3)


def test_pi5_pmic_through_a_vcgencmd_given_by_path(tmp_path):
    """pmic:vcgencmd runs the program vcgencmd= names (here a script standing in for a Pi 5's):
    each poll's watts are the sum of current x volts over the rails with both readings."""
    fake = tmp_path / "vcgencmd"
    fake.write_text("#!/bin/sh\n[ \"$1\" = pmic_read_adc ] || exit 2\n"
                    "echo '     3V3_SYS_A current(1)=0.10000000A'\necho '     VDD_CORE_A current(7)=2.00000000A'\n"
                    "echo '     3V3_SYS_V volt(9)=3.31002000V'\necho '     VDD_CORE_V volt(15)=0.80000000V'\n"
                    "echo '     EXT5V_V volt(24)=5.14647000V'\n")
    fake.chmod(0o700)
    s = trnkit.PowerSampler("pmic:vcgencmd", period_s=0.02, vcgencmd=fake)
    trace = s.sample(0.1)
    assert len(trace) >= 2
    np.testing.assert_allclose(trace.w, 2.0 * 0.8 + 0.1 * 3.31002, rtol=1e-12)
    with pytest.raises(trnkit.Error, match="absolute path"):
        trnkit.PowerSampler("pmic:vcgencmd", period_s=0.01, vcgencmd="vcgencmd").sample(0.02)
