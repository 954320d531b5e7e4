"""Backend.score against the trnkit CLI and the C++ rules: same inputs, same numbers."""
import subprocess

import numpy as np
import pytest

import trnkit
from conftest import backend_or_skip, texture, trnkit_exe, write_pgm

MAP = texture(300, 400)
TX, TY, TW, TH = 150, 100, 48, 40  # the template is cut from the map here
TEMPLATE = MAP[TY:TY + TH, TX:TX + TW]


def poses(n=300, seed=3):
    rng = np.random.default_rng(seed)
    p = np.column_stack([rng.uniform(-20, 420, n), rng.uniform(-20, 320, n), rng.uniform(-3.2, 3.2, n), rng.uniform(0.7, 1.4, n)])
    p[0] = [TX + (TW - 1) / 2, TY + (TH - 1) / 2, 0, 1]  # exactly where the template was cut
    return p.astype(np.float32)


def cli_scores(tmp_path, backend, pose_array, sampling):
    write_pgm(tmp_path / "map.pgm", MAP)
    write_pgm(tmp_path / "template.pgm", TEMPLATE)
    with open(tmp_path / "poses.csv", "w") as f:
        f.write("x,y,yaw,scale\n")
        for x, y, yaw, s in pose_array:
            f.write("%.9g,%.9g,%.9g,%.9g\n" % (x, y, yaw, s))  # 9 digits identify a float32
    out = subprocess.run([trnkit_exe(), "score", "--map", str(tmp_path / "map.pgm"), "--template", str(tmp_path / "template.pgm"),
                          "--poses", str(tmp_path / "poses.csv"), "--backend", backend, "--sampling", sampling],
                         capture_output=True, text=True, check=True).stdout
    rows = np.genfromtxt(out.splitlines()[1:], delimiter=",")
    return rows


@pytest.mark.parametrize("sampling_cli,sampling", [("dense", None), ("random:0.3:7", trnkit.Sampling.random(0.3, 7))])
@pytest.mark.parametrize("family", ["cpu-ref", "cpu", "opencl", "vulkan"])
def test_equals_cli(tmp_path, family, sampling_cli, sampling):
    b = backend_or_skip(family)
    p = poses()
    got = b.score(b.upload_map(MAP), TEMPLATE, p, sampling=sampling)
    want = cli_scores(tmp_path, b.name, p, sampling_cli)
    assert got.shape == (len(p),)
    # the CLI prints scores with 7 decimals
    for k, field in enumerate(["ncc", "cc", "ssd"]):
        np.testing.assert_allclose(got[field], want[:, 5 + k], atol=6e-8, err_msg=field)
    np.testing.assert_array_equal(got["valid_samples"], want[:, 8].astype(np.uint32))
    np.testing.assert_array_equal(got["flags"], want[:, 9].astype(np.uint32))
    assert abs(got["ncc"][0] - 1) < 1e-5 and got["flags"][0] == 0
    assert (got["flags"] == 0).sum() > 10 and (got["flags"] & trnkit.TOO_FEW_SAMPLES).sum() > 10


def test_structured_result(backend):
    s = backend.score(backend.upload_map(MAP), TEMPLATE, poses(5))
    assert s.dtype == trnkit.SCORE_DTYPE
    assert s.dtype.names == ("ncc", "cc", "ssd", "valid_samples", "flags")
    assert [s.dtype[n] for n in s.dtype.names] == [np.dtype(np.float32)] * 3 + [np.dtype(np.uint32)] * 2


def test_backends_agree(backend):
    ref = trnkit.Backend("cpu-ref")
    p = poses(500, seed=11)
    want = ref.score(ref.upload_map(MAP), TEMPLATE, p)
    got = backend.score(backend.upload_map(MAP), TEMPLATE, p)
    np.testing.assert_array_equal(got["valid_samples"], want["valid_samples"])
    np.testing.assert_array_equal(got["flags"], want["flags"])
    for field in ["ncc", "cc", "ssd"]:
        np.testing.assert_allclose(got[field], want[field], atol=1e-4)  # the conformance suite's tolerance


def test_layouts_and_types_give_the_same_scores():
    """Strided views (read in place), copies, float templates, float64 poses and Plans all agree."""
    b = trnkit.Backend("cpu")
    p = poses(200, seed=5)
    want = b.score(b.upload_map(np.ascontiguousarray(MAP)), np.ascontiguousarray(TEMPLATE), p)
    wide = np.zeros((300, 512), np.uint8)
    wide[:, :400] = MAP  # a view with row stride 512
    fortran = np.asfortranarray(MAP)  # column stride != 1: copied
    for m in [wide[:, :400], fortran]:
        np.testing.assert_array_equal(b.score(b.upload_map(m), TEMPLATE, p), want)
    m = b.upload_map(MAP)
    assert (m.width, m.height, m.backend) == (400, 300, "cpu")
    np.testing.assert_array_equal(b.score(m, TEMPLATE.astype(np.float32), p), want)
    np.testing.assert_array_equal(b.score(m, TEMPLATE.astype(np.float64), p.astype(np.float64)), want)
    upside_down = np.ascontiguousarray(TEMPLATE[::-1])
    np.testing.assert_array_equal(b.score(m, upside_down[::-1], p.tolist()), want)  # negative row stride: copied
    plan = trnkit.plan(TEMPLATE)
    assert (plan.width, plan.height, plan.sample_count) == (TW, TH, TW * TH)
    np.testing.assert_array_equal(b.score(m, plan, p), want)
    assert b.score(m, TEMPLATE, np.zeros((0, 4))).shape == (0,)


def test_sampling_and_min_valid_fraction():
    b = trnkit.Backend("cpu-ref")
    m = b.upload_map(MAP)
    p = poses(100, seed=9)
    dense = b.score(m, TEMPLATE, p)
    pts = np.array([[0, 0], [47, 39], [10, 5], [30, 20], [5, 33], [40, 2]])
    sparse = b.score(m, TEMPLATE, p, sampling=trnkit.Sampling.explicit(pts))
    assert trnkit.plan(TEMPLATE, trnkit.Sampling.explicit(pts)).sample_count == 6
    assert sparse["valid_samples"].max() == 6 and not np.array_equal(sparse["ncc"], dense["ncc"])
    lenient = b.score(m, TEMPLATE, p, min_valid_fraction=0.1)
    assert ((lenient["flags"] & trnkit.TOO_FEW_SAMPLES) != 0).sum() < ((dense["flags"] & trnkit.TOO_FEW_SAMPLES) != 0).sum()
    assert repr(trnkit.Sampling.random(0.5, 3)).startswith("Sampling.random(0.5")


def test_devices_lists_cpu():
    devices = trnkit.devices()
    names = [d["name"] for d in devices]
    assert "cpu-ref" in names and "cpu" in names
    assert set(devices[0]) == {"name", "family", "device", "type", "driver", "details"}
    out = subprocess.run([trnkit_exe(), "devices"], capture_output=True, text=True, check=True).stdout
    for n in names:
        assert n in out, f"{n} missing from `trnkit devices`"


def test_maps_are_read_in_place_when_rows_are_contiguous():
    """NumPy reports its allocations to tracemalloc: a copy of a 6 MB map would show."""
    import tracemalloc
    b = trnkit.Backend("cpu")
    big = np.zeros((2000, 4000), np.uint8)
    peaks = {}
    for name, a in [("contiguous", big), ("strided", big[:, :3000]), ("column-major", np.asfortranarray(big[:, :3000]))]:
        tracemalloc.start()
        b.upload_map(a)
        peaks[name] = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    assert peaks["contiguous"] < 100_000 and peaks["strided"] < 100_000, peaks
    assert peaks["column-major"] >= 6_000_000, peaks  # the copy is seen, so the check can fail


@pytest.mark.parametrize("family", ["cpu", "opencl", "vulkan"])
def test_no_data_mask(family):
    """valid= leaves samples on no-data out, as cpu-ref does, bit for bit; all-valid is no mask."""
    b, ref = backend_or_skip(family), trnkit.Backend("cpu-ref")
    valid = np.full(MAP.shape, 255, np.uint8)
    valid[:, :90] = 0
    valid[200:240, 250:300] = 0
    p = poses()
    got = b.score(b.upload_map(MAP, valid=valid), TEMPLATE, p, min_valid_fraction=0.0)
    want = ref.score(ref.upload_map(MAP, valid=valid), TEMPLATE, p, min_valid_fraction=0.0)
    plain = b.score(b.upload_map(MAP), TEMPLATE, p, min_valid_fraction=0.0)
    assert got.tobytes() == want.tobytes()
    assert (got["valid_samples"] <= plain["valid_samples"]).all()
    assert (got["valid_samples"] < plain["valid_samples"]).sum() > 20
    assert got[0].tobytes() == plain[0].tobytes()  # the template's own place has no no-data
    everything = b.score(b.upload_map(MAP, valid=np.ones(MAP.shape, np.uint8)), TEMPLATE, p, min_valid_fraction=0.0)
    assert everything.tobytes() == plain.tobytes()
    with pytest.raises(trnkit.Error, match="validity mask 10x10 differs from the map 400x300"):
        b.upload_map(MAP, valid=np.ones((10, 10), np.uint8))


def test_load_validity_reads_alpha(tmp_path):
    import os
    data = os.environ.get("TRN_SHARED_DATA", "")
    mosaic = os.path.join(data, "realflight2", "orthomosaic.png")
    if not data or not os.path.exists(mosaic):
        pytest.skip("TRN_SHARED_DATA/realflight2 not found")
    valid = trnkit.load_validity(mosaic)
    grey = trnkit.load_gray(mosaic)
    assert valid.shape == grey.shape and valid.dtype == np.uint8
    share = (valid == 0).mean()
    assert 0.3 < share < 0.6, share  # the README says 46 % no-data
    assert trnkit.load_validity(os.path.join(data, "orthophoto.png")) is None  # RGB: no alpha, no mask
    assert (trnkit.load_validity(os.path.join(data, "orthophoto.png"), nodata=0) is not None)
