"""trnkit.integrate_energy against `trnkit energy integrate` on the same files, and against the truth."""
import json
import subprocess

import numpy as np
import pytest

import trnkit
from energy_fixture import FRAMES, write_run
from conftest import trnkit_exe


def cli_report(log, markers, *args):
    out = subprocess.run([trnkit_exe(), "energy", "integrate", str(log), "--markers", str(markers), *args],
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)


@pytest.mark.parametrize("offset_ms,align,cli_args", [(0, "same-clock", []), (250, "auto", ["--align", "auto"])])
def test_equals_cli_and_truth(tmp_path, offset_ms, align, cli_args):
    log, markers = write_run(tmp_path, offset_ms)
    got = trnkit.integrate_energy(str(log), str(markers), align=align)
    want = cli_report(log, markers, *cli_args)
    assert len(got["net_j"]) == FRAMES == len(want["frames"])
    assert got["id"].tolist() == list(range(FRAMES))
    for field in ["id", "start_s", "end_s", "gross_j", "net_j", "error_j", "samples"]:
        np.testing.assert_allclose(got[field], [f[field] for f in want["frames"]], rtol=1e-12, err_msg=field)
    assert got["flag"] == [f["flag"] for f in want["frames"]] == [""] * FRAMES and got["usable"].all()
    assert got["align"] == want["config"]["align"]
    assert got["offset_s"] == pytest.approx(want["alignment"]["offset_s"], abs=1e-12)
    assert got["drift"] == pytest.approx(want["alignment"]["drift"], abs=1e-15)
    # the truth: 3 W above a 2 W idle for 200 ms
    assert abs(got["idle_w"] - 2.0) < 0.01
    assert np.all(np.abs(got["net_j"] - 0.6) <= got["error_j"] + 0.02)
    assert abs(got["offset_s"] - offset_ms / 1000) < 0.003
    assert got["samples"].dtype == np.uint64 and got["net_j"].dtype == np.float64


def test_options_reach_the_parser_and_rule(tmp_path):
    log, markers = write_run(tmp_path)
    trap = trnkit.integrate_energy(str(log), str(markers))
    hold = trnkit.integrate_energy(str(log), str(markers), rule="hold")
    assert not np.array_equal(trap["gross_j"], hold["gross_j"])
    strict = trnkit.integrate_energy(str(log), str(markers), min_samples=1000)
    assert not strict["usable"].any() and all("1000" in f for f in strict["flag"])
    with pytest.raises(trnkit.Error, match="nonsense"):
        trnkit.integrate_energy(str(log), str(markers), format="trnkit", options={"nonsense": "1"})


def test_bad_input_raises(tmp_path):
    log, markers = write_run(tmp_path)
    with pytest.raises(trnkit.Error, match="no-such.csv"):
        trnkit.integrate_energy(str(tmp_path / "no-such.csv"), str(markers))
    with pytest.raises(trnkit.Error, match=r"power-0.csv:1"):
        trnkit.integrate_energy(str(log), str(log))
    with pytest.raises(ValueError, match="align 'sideways'"):
        trnkit.integrate_energy(str(log), str(markers), align="sideways")
    with pytest.raises(ValueError, match="clock 'utc'"):
        trnkit.integrate_energy(str(log), str(markers), clock="utc")
