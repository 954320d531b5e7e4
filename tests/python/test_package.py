"""The package as Python users expect it: every BackendOptions field a keyword (errors name the
keyword), signatures and stubs that agree, units in the docstrings, out= and phase times, close()
and `with`, and clear errors or warnings for a single pose and for degrees."""
import ast
import inspect
import math
import os
import warnings

import numpy as np
import pytest

import trnkit
from conftest import backend_or_skip, texture

MAP = texture(200, 260, seed=8)
TEMPLATE = MAP[60:100, 80:128]
TRUE_POSE = [80 + 47 / 2, 60 + 39 / 2, 0.0, 1.0]


def poses(n=200, seed=4):
    rng = np.random.default_rng(seed)
    p = np.column_stack([rng.uniform(20, 240, n), rng.uniform(20, 180, n), rng.uniform(-3, 3, n), rng.uniform(0.8, 1.2, n)])
    p[0] = TRUE_POSE
    return p


def reference(p=None):
    ref = trnkit.Backend("cpu-ref")
    return ref.score(ref.upload_map(MAP), TEMPLATE, poses() if p is None else p)


# --- the package ---------------------------------------------------------------------------------

def test_is_a_package_with_stubs_and_py_typed():
    folder = os.path.dirname(trnkit.__file__)
    assert os.path.basename(trnkit.__file__) == "__init__.py"
    for name in ["__init__.pyi", "py.typed"]:
        assert os.path.exists(os.path.join(folder, name)), name
    assert trnkit._trnkit.__file__.startswith(folder)
    assert trnkit.Map.__module__ == "trnkit" == trnkit.Backend.__module__ == trnkit.PowerSampler.__module__
    import pickle
    times = pickle.loads(pickle.dumps(trnkit.PhaseTimes(1.0, 2.0, 3.0)))
    assert times.total_ms == 6.0 and type(times) is trnkit.PhaseTimes
    assert set(trnkit.__all__) <= set(dir(trnkit))


def stub_functions():
    """{qualified name: [parameter names]} of every function and method in __init__.pyi."""
    with open(os.path.join(os.path.dirname(trnkit.__file__), "__init__.pyi")) as f:
        tree = ast.parse(f.read())
    out = {}

    def params(fn):
        a = fn.args
        return [x.arg for x in a.posonlyargs + a.args + a.kwonlyargs] + (["*" + a.vararg.arg] if a.vararg else [])

    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            out[node.name] = params(node)
        elif isinstance(node, ast.ClassDef):
            for item in node.body:
                if not isinstance(item, ast.FunctionDef) or (item.name.startswith("__") and item.name != "__init__"):
                    continue  # __len__ & co.: protocol methods need no signature
                if not any(
                        isinstance(d, ast.Name) and d.id == "property" for d in item.decorator_list):
                    out[f"{node.name}.{item.name}"] = params(item)
    return out


def test_every_stub_function_has_that_runtime_signature():
    stubs = stub_functions()
    assert {"Backend.__init__", "Backend.score", "Sampling.random", "integrate_energy", "PowerSampler.__init__",
            "MeasurementWindows.frame"} <= set(stubs)
    for name, want in stubs.items():
        obj = trnkit
        for part in name.split("."):
            obj = getattr(obj, part)
        sig = inspect.signature(obj)  # a ValueError here: a compiled callable without a Python signature
        got = [("*" + p.name if p.kind is p.VAR_POSITIONAL else p.name) for p in sig.parameters.values()]
        assert got == want, f"{name}: runtime {got} != stub {want}"
    assert list(inspect.signature(trnkit.Backend).parameters)[:2] == ["spec", "threads"]


def test_docstrings_state_units_and_conventions():
    assert "RADIANS" in trnkit.__doc__ and "(x, y, yaw, scale)" in trnkit.__doc__
    doc = trnkit.Backend.score.__doc__
    for words in ["RADIANS", "(N, 4)", "map pixel", "flags", "SCORE_DTYPE", "out", "PhaseTimes"]:
        assert words in doc, words
    init = trnkit.Backend.__doc__
    for keyword in inspect.signature(trnkit.Backend).parameters:
        if keyword != "spec":
            assert keyword in init, f"Backend's docstring does not explain {keyword}"
    assert "milliseconds" in trnkit.PhaseTimes.__doc__ and "joules" in trnkit.integrate_energy.__doc__.lower()


# --- Backend keywords ----------------------------------------------------------------------------

def test_threads_and_simd_keywords_score_like_cpu_ref():
    want = reference()
    for kw in [dict(threads=1), dict(threads=3, simd=False), dict(threads=np.int64(2))]:
        with trnkit.Backend("cpu", **kw) as b:
            np.testing.assert_array_equal(b.score(b.upload_map(MAP), TEMPLATE, poses()), want, err_msg=str(kw))


@pytest.mark.parametrize("kw,error,text", [
    (dict(threads=1.5), TypeError, "threads must be an int, not float"),
    (dict(threads=True), TypeError, "threads must be an int, not bool"),
    (dict(threads=-1), ValueError, "threads=-1"),
    (dict(threads=5000), trnkit.Error, r"threads=5000: expected 0 \(the hardware threads\) to 4096"),
    (dict(simd="off"), TypeError, "simd must be True or False, not str"),
    (dict(work_group=48), ValueError, "work_group=48: expected 0 .* or a power of two"),
    (dict(cache_dir=3), TypeError, "cache_dir must be a str or os.PathLike"),
    (dict(particles_per_group=17), ValueError, "particles_per_group=17: expected 0 to 16"),
    (dict(opencl_device=-2), ValueError, "opencl_device=-2"),
    (dict(nonsense=1), TypeError, "nonsense"),
])
def test_bad_keywords_name_the_keyword(kw, error, text):
    spec = "vulkan" if "particles_per_group" in kw else "opencl" if "opencl_device" in kw or "work_group" in kw or "cache_dir" in kw else "cpu"
    with pytest.raises(error, match=text) as e:
        trnkit.Backend(spec, **kw)
    assert "TRN_" not in str(e.value) and "BackendOptions" not in str(e.value)


def test_a_keyword_of_another_family_is_refused():
    with pytest.raises(ValueError, match="threads is an option of cpu backends, not of 'opencl'"):
        trnkit.Backend("opencl", threads=2)
    with pytest.raises(ValueError, match="particles_per_group is an option of vulkan backends, not of 'cpu'"):
        trnkit.Backend("cpu", particles_per_group=4)
    with pytest.raises(ValueError, match="work_group is an option of opencl and vulkan backends, not of 'cpu-ref'"):
        trnkit.Backend("cpu-ref", work_group=64)
    trnkit.Backend("cpu", threads=0, work_group=0)  # a default is no option given


def test_opencl_keywords(tmp_path):
    backend_or_skip("opencl")
    want = reference()
    cache = tmp_path / "programs"
    with trnkit.Backend("opencl", opencl_device=0, work_group=64, cache_dir=cache) as b:
        assert b.name == "opencl:0"
        np.testing.assert_array_equal(b.score(b.upload_map(MAP), TEMPLATE, poses()), want)
    assert any(cache.iterdir()), "cache_dir got no compiled program"
    with pytest.raises(trnkit.BackendUnavailable, match="no-such-device"):
        trnkit.Backend("opencl", opencl_device="no-such-device")


def test_vulkan_keywords(tmp_path):
    backend_or_skip("vulkan")
    want = reference()
    for kw in [dict(work_group=64, particles_per_group=4), dict(quad_maps=False, subgroups=False, force_staging=True),
               dict(vulkan_device=0, cache_dir=tmp_path, validation=True)]:
        with trnkit.Backend("vulkan", **kw) as b:
            np.testing.assert_array_equal(b.score(b.upload_map(MAP), TEMPLATE, poses()), want, err_msg=str(kw))
    assert any(tmp_path.iterdir()), "cache_dir got no pipeline cache"
    with pytest.raises(ValueError, match="work_group=2048: expected 0 .* up to 1024"):
        trnkit.Backend("vulkan", work_group=2048)


def test_fastest_takes_every_keyword():
    b = trnkit.Backend("fastest", threads=1, work_group=64)
    assert b.score(b.upload_map(MAP), TEMPLATE, [TRUE_POSE])["ncc"][0] == pytest.approx(1, abs=1e-5)


# --- score: out=, phase times, poses and units ---------------------------------------------------

def test_out_and_return_times(backend):
    m, p = backend.upload_map(MAP), poses()
    out = np.zeros(len(p), trnkit.SCORE_DTYPE)
    got = backend.score(m, TEMPLATE, p, out=out)
    assert got is out
    np.testing.assert_array_equal(out, reference())
    scores, times = backend.score(m, trnkit.plan(TEMPLATE), p, return_times=True)
    np.testing.assert_array_equal(scores, out)
    assert isinstance(times, trnkit.PhaseTimes) and times.execute_ms > 0
    assert times.total_ms == pytest.approx(times.upload_ms + times.execute_ms + times.download_ms)
    scores, times = backend.score(m, TEMPLATE, p, out=out, return_times=True)
    assert scores is out and times.total_ms > 0
    m2, up = backend.upload_map(MAP, return_times=True)
    assert isinstance(m2, trnkit.Map) and up.total_ms >= 0
    gx, gy, st = backend.sobel(MAP, return_times=True)
    assert gx.shape == MAP.shape and st.total_ms > 0


def test_bad_out_arrays_name_out():
    b = trnkit.Backend("cpu")
    m, p = b.upload_map(MAP), poses(10)
    for bad, error, text in [(np.zeros(9, trnkit.SCORE_DTYPE), ValueError, r"shape \(10,\).*got shape \(9,\)"),
                             (np.zeros(10, np.float32), ValueError, "dtype"),
                             (np.zeros(20, trnkit.SCORE_DTYPE)[::2], ValueError, "strided"),
                             ([0] * 10, TypeError, "out must be")]:
        with pytest.raises(error, match=text):
            b.score(m, TEMPLATE, p, out=bad)
    ro = np.zeros(10, trnkit.SCORE_DTYPE)
    ro.flags.writeable = False
    with pytest.raises(ValueError, match="read-only"):
        b.score(m, TEMPLATE, p, out=ro)


def test_a_single_pose_says_how_to_pass_it():
    b = trnkit.Backend("cpu")
    m = b.upload_map(MAP)
    with pytest.raises(ValueError, match=r"poses has shape \(4,\), a single pose: pass shape \(1, 4\)"):
        b.score(m, TEMPLATE, np.array(TRUE_POSE))
    with pytest.raises(ValueError, match=r"single pose"):
        b.score(m, TEMPLATE, TRUE_POSE)
    assert b.score(m, TEMPLATE, np.array(TRUE_POSE)[None])["ncc"][0] == pytest.approx(1, abs=1e-5)


def test_degrees_are_warned_radians_are_not():
    b = trnkit.Backend("cpu")
    m = b.upload_map(MAP)
    p = poses()
    degrees = p.copy()
    degrees[:, 2] = np.degrees(p[:, 2]) % 360 + 10  # every |yaw| > 2 pi
    with pytest.warns(trnkit.YawUnitWarning, match="yaw is in radians") as w:
        b.score(m, TEMPLATE, degrees)
    assert w[0].filename == __file__  # points at the caller's line
    spread = p.copy()
    spread[:, 2] = np.random.default_rng(1).uniform(0, 360, len(p))  # some below 2 pi, but 360 wide
    spread[0, 2] = 0
    with pytest.warns(trnkit.YawUnitWarning):
        b.score(m, TEMPLATE, spread.tolist())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        b.score(m, TEMPLATE, p)                  # radians in [-pi, pi]
        unwrapped = p.copy()
        unwrapped[:, 2] = p[:, 2] / 10 + 4 * math.pi   # an unwrapped heading, two turns on: a narrow cloud
        unwrapped[0, 2] = 1.0
        b.score(m, TEMPLATE, unwrapped)
        b.score(m, TEMPLATE, np.zeros((0, 4)))


# --- close() and `with` --------------------------------------------------------------------------

def test_close_releases_maps_and_refuses_later_calls():
    with trnkit.Backend("cpu") as b:
        m = b.upload_map(MAP)
        assert not b.closed and "closed" not in repr(b)
    assert b.closed and repr(b) == "trnkit.Backend('cpu', closed)"
    with pytest.raises(trnkit.Error, match="backend 'cpu' is closed"):
        b.score(m, TEMPLATE, [TRUE_POSE])
    with pytest.raises(trnkit.Error, match="closed"):
        b.upload_map(MAP)
    with pytest.raises(trnkit.Error, match="closed"):
        b.sobel(MAP)
    assert "released" in repr(m) and (m.width, m.height, m.backend) == (260, 200, "cpu")
    b.close()  # again: nothing


def test_a_map_of_a_closed_backend_on_another_backend():
    a, b = trnkit.Backend("cpu"), trnkit.Backend("cpu")
    m = a.upload_map(MAP)
    a.close()
    with pytest.raises(trnkit.Error, match="released when its backend 'cpu' was closed"):
        b.score(m, TEMPLATE, [TRUE_POSE])


def test_families_and_sampling():
    assert {"cpu-ref", "cpu"} <= set(trnkit.families())
    assert trnkit.Sampling.random(0.5).kind == "random" and trnkit.Sampling.dense().kind == "dense"
    assert trnkit.Sampling.explicit([[0, 0], [1, 1]]).kind == "explicit"
    with pytest.raises(TypeError, match="seed must be an int"):
        trnkit.Sampling.random(0.5, seed=1.5)
