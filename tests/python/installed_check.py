"""Run by test_pip.py with the python of a venv the trnkit wheel was installed into (no PYTHONPATH,
cwd outside the checkout): the package found is the installed one, self-contained (the
libtrnkit_* beside the extension, RUNPATH $ORIGIN, nothing from the checkout or build tree), it
scores bit-identically to cpu-ref on every required backend, and its signatures and stubs work.
Plain asserts, no pytest: any CPython with NumPy runs it."""
import inspect
import os
import subprocess
import sys

import numpy as np

import trnkit

folder = os.path.dirname(os.path.realpath(trnkit.__file__))
assert folder.startswith(os.path.realpath(sys.prefix)), f"{trnkit.__file__} is not in the venv {sys.prefix}"
files = sorted(os.listdir(folder))
for want in ["__init__.py", "__init__.pyi", "py.typed", "_backend.py", "_energy.py"]:
    assert want in files, (want, files)
libs = [f for f in files if f.startswith("libtrnkit_")]
assert any(f.startswith("libtrnkit_core.so") for f in libs) and any(f.startswith("libtrnkit_energy.so") for f in libs), files
for f in [f for f in files if f.startswith("_trnkit")] + libs:
    dyn = subprocess.run(["readelf", "-d", os.path.join(folder, f)], capture_output=True, text=True, check=True).stdout
    paths = [l.split("[", 1)[1].rstrip("]") for l in dyn.splitlines() if "(RUNPATH)" in l or "(RPATH)" in l]
    assert paths in ([], ["$ORIGIN"]), f"{f}: RUNPATH {paths}"
maps = open("/proc/self/maps").read()
loaded = {line.split()[-1] for line in maps.splitlines() if "libtrnkit_" in line or "_trnkit" in line}
assert loaded and all(os.path.realpath(p).startswith(folder + "/") for p in loaded), loaded  # none from a build tree

rng = np.random.default_rng(5)
ortho = rng.integers(0, 256, (300, 400), dtype=np.uint8)
ortho = np.cumsum(np.cumsum(ortho, 0), 1).astype(np.uint8)  # some structure
templ = ortho[100:140, 150:198]
poses = np.c_[rng.uniform(0, 400, (500, 2)), rng.uniform(-3, 3, 500), rng.uniform(0.8, 1.2, 500)]
poses[0] = [150 + 47 / 2, 100 + 39 / 2, 0, 1]
with trnkit.Backend("cpu-ref") as ref:
    want = ref.score(ref.upload_map(ortho), templ, poses)
required = [f for f in os.environ.get("TRN_REQUIRE_BACKENDS", "").replace(",", ";").split(";") if f]
assert set(required) <= set(trnkit.families()), (required, trnkit.families())
scored = []
for family in ["cpu-ref", "cpu", "opencl", "vulkan"]:
    try:
        b = trnkit.Backend(family)
    except trnkit.BackendUnavailable as e:
        assert family not in required, f"{family} is required but NOT AVAILABLE: {e}"
        print(f"installed check: {family} NOT AVAILABLE: {e}")
        continue
    with b:
        got = b.score(b.upload_map(ortho), templ, poses)
    assert got.tobytes() == want.tobytes(), f"{family} differs from cpu-ref"
    scored.append(b.name)
assert want["ncc"][0] > 0.99999

assert list(inspect.signature(trnkit.Backend).parameters)[:2] == ["spec", "threads"]
inspect.signature(trnkit.Backend.score), inspect.signature(trnkit.integrate_energy)
print(f"installed check: Python {sys.version.split()[0]} at {sys.executable}, numpy {np.__version__}, trnkit {trnkit.__version__}"
      f" from {folder}; bit-identical to cpu-ref on {', '.join(scored)}")
