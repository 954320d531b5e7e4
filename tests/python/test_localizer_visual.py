"""Visual odometry online (issue 43 item 4): trnkit.Localizer(visual_odometry=True), fed the real
flight's frames row by row WITHOUT odometry, computes the odometry from the frames as `trnkit localize
--odometry visual` does, and gives its estimates bit for bit (trnkit.localize(odometry="visual")) and
to the CSV's 10 digits (the CLI); odometry the caller gives is used as given. Skipped (visibly)
without ../shared/data."""
import csv
import os
import subprocess

import numpy as np
import pytest

import trnkit
from test_doc_example import doc_example
from test_localizer import flight, shared_data  # noqa: F401 (the real flight's AIR folder, a pytest fixture)


def without_odometry(step):
    s = dict(step)
    s["odometry"] = None
    s["odometry_yaw_rad"] = None
    return s


def test_visual_odometry_online_equals_localize_and_the_cli(flight, tmp_path):  # noqa: F811
    air, ortho = flight
    whole = trnkit.localize(dataset=air, map=ortho, backend="cpu", rate_hz=0.5, odometry="visual")
    rows = trnkit.read_air_folder(air)
    with trnkit.Localizer(trnkit.load_gray(ortho), whole["metres_per_pixel"], "cpu", start=rows[0]["truth"], camera_hfov_deg=60,
                          init_radius_m=50, visual_odometry=True) as loc:
        online = [loc.step(**without_odometry(row["step"])) for row in rows]
    for key in ("x", "y", "yaw"):
        np.testing.assert_array_equal(np.array([e[key] for e in online]), whole["rows"]["estimate_" + key])
    assert online[0]["odometry_source"] == "visual:start" and online[1]["odometry_source"].startswith("visual:")
    out = str(tmp_path / "cli")
    subprocess.run([os.environ["TRNKIT_EXE"], "localize", "--dataset", air, "--map", ortho, "--rate", "0.5", "--no-plots", "--backend",
                    "cpu", "--init-radius-m", "50", "--seed", "1", "--odometry", "visual", "--out", out], check=True, capture_output=True)
    with open(os.path.join(out, "localization.csv")) as f:
        cli = list(csv.DictReader(f))
    for key in ("x", "y", "yaw"):
        assert [r["estimate_" + key] for r in cli] == ["%.10g" % e[key] for e in online]


def test_compassless_visual_odometry_online_equals_localize(flight):  # noqa: F811
    air, ortho = flight
    whole = trnkit.localize(dataset=air, map=ortho, backend="cpu", rate_hz=0.5, odometry="visual", heading="none", max_particles=3000)
    rows = trnkit.read_air_folder(air)
    with trnkit.Localizer(trnkit.load_gray(ortho), whole["metres_per_pixel"], "cpu", start=rows[0]["truth"], camera_hfov_deg=60,
                          init_radius_m=50, max_particles=3000, heading="none", visual_odometry=True) as loc:
        online = [loc.step(**without_odometry(row["step_without_compass"])) for row in rows]
    for key in ("x", "y", "yaw", "yaw_sd"):
        np.testing.assert_array_equal(np.array([e[key] for e in online]), whole["rows"]["estimate_" + key])


def test_odometry_given_wins_over_the_visual():
    rng = np.random.default_rng(3)
    ortho = rng.integers(0, 256, (300, 300), dtype=np.uint8)
    frame = np.ascontiguousarray(ortho[100:160, 110:190])
    assert trnkit.localizer_defaults()["visual_odometry"] is False
    runs = {}
    for visual in (False, True):
        with trnkit.Localizer(ortho, 1.0, "cpu", start=(150, 130), start_heading_rad=0.0, visual_odometry=visual) as loc:
            runs[visual] = [loc.step(frame, odometry=(1.0, -0.5), heading_rad=0.0, scale=1.0) for _ in range(3)]
    assert [e["odometry_source"] for e in runs[True]] == ["given"] * 3 == [e["odometry_source"] for e in runs[False]]
    for a, b in zip(runs[True], runs[False]):
        assert (a["x"], a["y"], a["yaw"]) == (b["x"], b["y"], b["yaw"])
    with trnkit.Localizer(ortho, 1.0, "cpu", start=(150, 130), start_heading_rad=0.0) as loc:
        assert loc.step(frame, heading_rad=0.0, scale=1.0)["odometry_source"] == "none"
    with trnkit.Localizer(ortho, 1.0, "cpu", start=(150, 130), start_heading_rad=0.0, visual_odometry=True) as loc:
        assert [loc.step(frame, heading_rad=0.0, scale=1.0)["odometry_source"] for _ in range(2)][0] == "visual:start"


def test_the_doc_example_runs_visual_odometry_on_the_real_flight(flight, capsys):  # noqa: F811
    air, map_path = flight
    mpp = trnkit.localize(dataset=air, map=map_path, backend="cpu", rate_hz=0.5)["metres_per_pixel"]
    exec(compile(doc_example("visual_odometry.py"), "EMBEDDING.md:visual_odometry.py", "exec"), {"air": air, "map_path": map_path, "mpp": mpp})
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 16 and lines[0].startswith("visual:start") and all(l.startswith("visual:") for l in lines)
