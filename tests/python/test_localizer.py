"""trnkit.Localizer on the real flight (issue 24): fed row by row from trnkit.read_air_folder it gives
trnkit.localize's estimates bit for bit, and both equal `trnkit localize` to the CSV's 10 digits;
docs/EMBEDDING.md's localize_flight.py runs as written; errors name the keyword. The AIR folder is
made from ../shared/data/realflight by `trnkit register --air-out` (skipped visibly without it)."""
import csv
import os
import subprocess

import numpy as np
import pytest

import trnkit
from conftest import backend_or_skip
from test_doc_example import doc_example

HERE = os.path.dirname(os.path.abspath(__file__))
POSES = os.path.join(HERE, "..", "data", "realflight_poses.csv")


def shared_data():
    d = os.environ.get("TRN_SHARED_DATA", "")
    if not d or not os.path.exists(os.path.join(d, "realflight", "frame_00000.png")):
        pytest.skip("TRN_SHARED_DATA/realflight not found: real flight unavailable")
    return d


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    data = shared_data()
    air = str(tmp_path_factory.mktemp("realflight") / "air")
    ortho = os.path.join(data, "orthophoto.png")
    frames = sorted(os.path.join(data, "realflight", f) for f in os.listdir(os.path.join(data, "realflight")) if f.startswith("frame_000"))
    subprocess.run([os.environ["TRNKIT_EXE"], "register", "--map", ortho, "--verify", POSES, "--air-out", air, *frames],
                   check=True, capture_output=True)
    return air, ortho


def cli_estimates(air, ortho, backend, out):
    subprocess.run([os.environ["TRNKIT_EXE"], "localize", "--dataset", air, "--map", ortho, "--rate", "0.5", "--no-plots",
                    "--backend", backend, "--init-radius-m", "50", "--seed", "1", "--out", out], check=True, capture_output=True)
    with open(os.path.join(out, "localization.csv")) as f:
        return list(csv.DictReader(f))


@pytest.mark.parametrize("family", ["cpu-ref", "cpu", "opencl", "vulkan"])
def test_localizer_row_by_row_equals_localize_and_the_cli(flight, family, tmp_path):
    backend_or_skip(family)
    air, ortho = flight
    whole = trnkit.localize(dataset=air, map=ortho, backend=family, rate_hz=0.5)
    rows = trnkit.read_air_folder(air)
    assert len(rows) == 16 and whole["summary"]["steps"] == 16
    mpp = whole["metres_per_pixel"]
    with trnkit.Localizer(trnkit.load_gray(ortho), mpp, family, start=rows[0]["truth"], camera_hfov_deg=60,
                          init_radius_m=50) as loc:
        online = [loc.step(**row["step"]) for row in rows]
    for key in ("x", "y", "yaw"):
        np.testing.assert_array_equal(np.array([e[key] for e in online]), whole["rows"]["estimate_" + key])
    cli = cli_estimates(air, ortho, family, str(tmp_path / "cli"))
    for key in ("x", "y", "yaw"):
        assert [r["estimate_" + key] for r in cli] == ["%.10g" % v for v in whole["rows"]["estimate_" + key]]
    assert whole["summary"]["filter_mean_error_m"] < whole["summary"]["odometry_mean_error_m"]


def test_the_doc_example_localizes_the_real_flight(flight, capsys):
    air, map_path = flight
    ns = {"air": air, "map_path": map_path}
    exec(compile(doc_example("localize_flight.py"), "EMBEDDING.md:localize_flight.py", "exec"), ns)
    assert len(ns["estimates"]) == 16
    assert "16 steps" in capsys.readouterr().out


def test_compassless_localizer_row_by_row_equals_localize(flight):
    """heading="none" (issue 25): fed step_without_compass row by row, the Localizer gives
    trnkit.localize(heading="none")'s estimates bit for bit; yaw is an output with its spread."""
    air, ortho = flight
    whole = trnkit.localize(dataset=air, map=ortho, backend="cpu", rate_hz=0.5, heading="none", max_particles=3000)
    rows = trnkit.read_air_folder(air)
    assert rows[0]["step_without_compass"]["heading_rad"] is None and rows[0]["step_without_compass"]["odometry_yaw_rad"] == 0
    with trnkit.Localizer(trnkit.load_gray(ortho), whole["metres_per_pixel"], "cpu", start=rows[0]["truth"], camera_hfov_deg=60,
                          init_radius_m=50, max_particles=3000, heading="none") as loc:
        online = [loc.step(**row["step_without_compass"]) for row in rows]
    for key in ("x", "y", "yaw", "yaw_sd"):
        np.testing.assert_array_equal(np.array([e[key] for e in online]), whole["rows"]["estimate_" + key])
    assert online[0]["yaw_sd"] > 0.3 > online[-1]["yaw_sd"]  # a uniform prior narrows to a heading
    s = whole["summary"]
    assert s["final_yaw_sd_deg"] < 10 and s["mean_yaw_error_deg"] < 10 and s["converged_from_frame"] is not None


def test_dissertation_profile_row_by_row_equals_localize(flight):
    """profile="dissertation" (issue 27): the Localizer fed row by row gives
    trnkit.localize(profile="dissertation")'s estimates bit for bit; its lock monitor is off (on
    with lock_monitor=True), and it is not ours' run."""
    air, ortho = flight
    whole = trnkit.localize(dataset=air, map=ortho, backend="cpu", rate_hz=0.5, profile="dissertation", max_particles=3000)
    ours = trnkit.localize(dataset=air, map=ortho, backend="cpu", rate_hz=0.5, max_particles=3000, init_radius_m=300)
    rows = trnkit.read_air_folder(air)
    with trnkit.Localizer(trnkit.load_gray(ortho), whole["metres_per_pixel"], "cpu", start=rows[0]["truth"], camera_hfov_deg=60,
                          max_particles=3000, profile="dissertation") as loc:
        online = [loc.step(**row["step"]) for row in rows]
    for key in ("x", "y"):
        np.testing.assert_array_equal(np.array([e[key] for e in online]), whole["rows"]["estimate_" + key])
    assert {e["lock_state"] for e in online} == {"none"}
    assert not np.array_equal(whole["rows"]["estimate_x"], ours["rows"]["estimate_x"])
    with trnkit.Localizer(trnkit.load_gray(ortho), whole["metres_per_pixel"], "cpu", start=rows[0]["truth"], camera_hfov_deg=60,
                          max_particles=3000, profile="dissertation", lock_monitor=True) as loc:
        assert {loc.step(**row["step"])["lock_state"] for row in rows} != {"none"}
    with pytest.raises(ValueError, match=r"^profile: .*dissertation"):
        trnkit.Localizer(np.zeros((64, 64), np.uint8), 0.5, "cpu", start=(32, 32), profile="literal")


def test_errors_name_the_keyword(tmp_path):
    with pytest.raises(ValueError, match=r"^dataset: .*not a folder"):
        trnkit.localize(dataset=str(tmp_path / "absent"))
    ortho = np.zeros((64, 64), np.uint8)
    with pytest.raises(TypeError):
        trnkit.Localizer(ortho, 0.5, "cpu")  # start is required
    with pytest.raises(ValueError, match="sparse"):
        trnkit.Localizer(ortho, 0.5, "cpu", start=(32, 32), sparse=2)
    with pytest.raises(ValueError, match="conversion"):
        trnkit.Localizer(ortho, 0.5, "cpu", start=(32, 32), conversion="cubic")
    with pytest.raises(ValueError, match="^heading: "):
        trnkit.Localizer(ortho, 0.5, "cpu", start=(32, 32), heading="north")
    with trnkit.Localizer(ortho, 0.5, "cpu", start=(32, 32), heading="none", start_heading_rad=1.0, start_heading_sd_deg=2) as loc:
        e = loc.step(None, odometry=(0.0, 1.0), odometry_yaw_rad=0.25)  # a Gaussian yaw prior turned by the odometry
        assert abs(e["yaw"] - 1.25) < 0.02 and e["yaw_sd"] < 0.1
    with trnkit.Localizer(ortho, 0.5, "cpu", start=(32, 32)) as loc:
        with pytest.raises(ValueError, match="altitude_agl_m"):
            loc.step(np.zeros((20, 20), np.uint8))  # a frame needs its scale
        e = loc.step(None, odometry=(1.0, 0.0))  # no frame: propagated, not scored
        assert e["frame_missing"]
    with pytest.raises(ValueError, match="closed"):
        loc.step(None)


def test_a_backend_with_keywords_serves_the_localizer_and_closing_it_releases_the_localizer(flight):
    air, ortho = flight
    rows = trnkit.read_air_folder(air)[:3]
    want = trnkit.localize(dataset=air, map=ortho, backend="cpu", rate_hz=0.5)["rows"]["estimate_x"][:3]
    backend = trnkit.Backend("cpu", threads=1)
    whole = trnkit.localize(dataset=air, map=ortho, backend=backend, rate_hz=0.5)  # a Backend serves localize too
    np.testing.assert_array_equal(whole["rows"]["estimate_x"][:3], want)
    loc = trnkit.Localizer(trnkit.load_gray(ortho), 0.5, backend, start=rows[0]["truth"], camera_hfov_deg=60, init_radius_m=50)
    got = [loc.step(**row["step"])["x"] for row in rows]
    np.testing.assert_array_equal(got, want)  # one thread or all: the same bits
    backend.close()
    with pytest.raises(ValueError, match="closed"):
        loc.step(None)


def stub_estimate_keys():
    """The keys of the Estimate TypedDict in the package's stubs."""
    import ast
    stub = os.path.join(os.path.dirname(trnkit.__file__), "__init__.pyi")
    with open(stub) as f:
        tree = ast.parse(f.read())
    for node in tree.body:
        if isinstance(node, ast.ClassDef) and node.name == "Estimate":
            return {item.target.id for item in node.body if isinstance(item, ast.AnnAssign)}
    raise AssertionError("no Estimate in " + stub)


def test_estimates_carry_covariance_latlon_time_and_velocity_as_typed():
    """Issue 43 item 2: the online estimate has what an autopilot takes, under the stub's names."""
    rng = np.random.default_rng(3)
    ortho = (rng.random((400, 400)) * 255).astype(np.uint8)
    with trnkit.Localizer(ortho, 0.5, "cpu", start=(200, 200), init_radius_m=20, map_origin=(41.0, -83.3)) as loc:
        first = loc.step(None, odometry=(0.0, 0.0), heading_rad=0.0, time_s=10.0)
        second = loc.step(None, odometry=(4.0, 0.0), heading_rad=0.0, time_s=12.0)
    assert set(second) == stub_estimate_keys()
    assert first["vel_east_mps"] is None and first["time_s"] == 10.0
    assert second["vel_east_mps"] == pytest.approx((second["x"] - first["x"]) * 0.5 / 2)
    assert second["vel_var_m2ps2"] > 0
    assert second["cov_ee_m2"] == pytest.approx(second["cov_xx_px2"] * 0.25)
    assert second["cov_ne_m2"] == pytest.approx(-second["cov_xy_px2"] * 0.25)
    assert second["eph_m"] ** 2 <= second["cov_nn_m2"] + second["cov_ee_m2"] + 1e-9
    assert 40.99 < second["latitude_deg"] < 41.0 and -83.3 < second["longitude_deg"] < -83.29
    with trnkit.Localizer(ortho, 0.5, "cpu", start=(200, 200)) as loc:
        plain = loc.step(None, odometry=(0.0, 0.0), heading_rad=0.0)
    assert plain["latitude_deg"] is None and plain["time_s"] is None
    with pytest.raises(trnkit.Error, match="map_origin"):
        trnkit.Localizer(ortho, 0.5, "cpu", start=(200, 200), map_origin=(95.0, 0.0))


def textured(size=400, seed=3):
    rng = np.random.default_rng(seed)
    small = (rng.random((size // 8, size // 8)) * 255).astype(np.uint8)
    return np.kron(small, np.ones((8, 8), np.uint8))  # blobs an 8-px patch can be told apart by


def test_reanchor_starts_over_at_the_fix_with_the_settings_kept():
    """Issue 43 item 4: a new GNSS fix re-anchors the filter there, lock state unknown again."""
    ortho = textured()
    with trnkit.Localizer(ortho, 0.5, "cpu", start=(100, 100), start_heading_rad=0.0) as loc:
        for _ in range(2):
            loc.step(ortho[60:140, 50:150].copy(), odometry=(0.0, 0.0), heading_rad=0.0, scale=1.0)
        loc.reanchor((300, 250), radius_m=5)
        e = loc.step(ortho[210:290, 250:350].copy(), odometry=(0.0, 0.0), heading_rad=0.0, scale=1.0)
        assert np.hypot(e["x"] - 300, e["y"] - 250) * 0.5 < 5
        assert e["lock_state"] == "unknown" and e["vel_east_mps"] is None
        with pytest.raises(trnkit.Error, match=r"400x400 px map"):
            loc.reanchor((5000, 250), radius_m=5)
        with pytest.raises(trnkit.Error, match="radius_m"):
            loc.reanchor((300, 250), radius_m=0)
    with pytest.raises(trnkit.Error, match="closed"):  # docs/EMBEDDING.md: a closed Localizer raises trnkit.Error
        loc.reanchor((300, 250), radius_m=5)
    with pytest.raises(trnkit.Error, match="closed"):
        loc.step(None)


def test_the_traps_of_issue_43_are_refused_in_user_terms():
    import copy
    ortho = textured()
    frame = ortho[60:140, 50:150].copy()
    with pytest.raises(trnkit.Error, match=r"outside the 400x400 px map"):
        trnkit.Localizer(ortho, 0.5, "cpu", start=(5000, 100))
    with pytest.raises(trnkit.Error, match=r"camera_hfov_deg.*\[5, 170\].*radians\?"):
        trnkit.Localizer(ortho, 0.5, "cpu", start=(100, 100), camera_hfov_deg=1.2)
    with pytest.raises(TypeError) as wrong:
        trnkit.Localizer(ortho, "half", "cpu", start=(100, 100))
    assert "_trnkit" not in str(wrong.value) and "trnkit.Localizer" in str(wrong.value)
    with trnkit.Localizer(ortho, 0.5, "cpu", start=(100, 100), camera_hfov_deg=60) as loc:
        for clone in (copy.copy, copy.deepcopy):
            with pytest.raises(TypeError, match="cannot be copied"):
                clone(loc)
        with pytest.raises(trnkit.Error, match="ambiguous"):
            loc.step(frame, odometry=(0.0, 0.0), heading_rad=0.0, scale=1.0, altitude_agl_m=100.0)
        with pytest.raises(trnkit.Error, match="radians"):
            loc.step(frame, odometry=(0.0, 0.0), heading_rad=0.0, scale=1.0, attitude=(3.0, 15.0))
        with pytest.raises(trnkit.Error, match="start_heading_rad"):  # compass mode, no heading ever
            loc.step(frame, odometry=(0.0, 0.0), scale=1.0)
        with pytest.raises(trnkit.Error, match="altitude_agl_m") as low:
            loc.step(frame, odometry=(0.0, 0.0), heading_rad=0.0, altitude_agl_m=-2.0)
        assert "template_scale" not in str(low.value)
        with pytest.raises(trnkit.Error, match='heading "none"'):  # odometry in the frame's axes to a compass Localizer
            loc.step(None, odometry=(0.0, 1.0), odometry_yaw_rad=0.1)
    with trnkit.Localizer(ortho, 0.5, "cpu", start=(100, 100), heading="none", start_heading_rad=0.0) as loc:
        with pytest.raises(trnkit.Error, match="previous frame's axes"):  # compass-style input to a compass-less one
            loc.step(None, odometry=(1.0, 0.0), heading_rad=0.3)


def test_load_map_keeps_the_no_data_as_the_cli_reads_it():
    data = os.environ.get("TRN_SHARED_DATA", "")
    path = os.path.join(data, "realflight2", "orthomosaic.png")
    if not data or not os.path.exists(path):
        pytest.skip("TRN_SHARED_DATA/realflight2 not found: no map with alpha")
    image, valid = trnkit.load_map(path)
    np.testing.assert_array_equal(image, trnkit.load_gray(path))
    np.testing.assert_array_equal(valid, trnkit.load_validity(path))
    assert valid is not None and 0.3 < (valid == 0).mean() < 0.6  # the README: 46 % no-data
