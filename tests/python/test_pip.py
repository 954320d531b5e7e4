"""`pip install .` and `pip wheel .` of the checkout, with no network and Debian's build tools
(setuptools driving CMake, --no-build-isolation), into fresh venvs; the installed package is then
checked by installed_check.py: self-contained, bit-identical to cpu-ref on every backend. Also in a
CPython 3.11 that is not Debian's (pyenv's, when present), with Debian's NumPy made importable.
Timings of each pip step are printed (pytest -s, or ctest -V)."""
import glob
import os
import shutil
import subprocess
import sys
import time
import zipfile

import pytest

SOURCE = os.environ.get("TRN_SOURCE_DIR") or os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WORK = os.environ.get("TRN_PIP_WORK") or "/tmp/trnkit-pip-test"
CHECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "installed_check.py")
# Another CPython 3.11 (not Debian's); TRN_OTHER_PYTHON names one elsewhere.
OTHER_PYTHON = os.environ.get("TRN_OTHER_PYTHON") or next(iter(sorted(glob.glob(os.path.expanduser("~/.pyenv/versions/3.11.*/bin/python3")))), "")


def run(cmd, **kw):
    t0 = time.monotonic()
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env.update(kw.pop("env", {}))
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, **kw)
    took = time.monotonic() - t0
    if out.returncode != 0:
        pytest.fail(f"{' '.join(cmd)} failed ({out.returncode}) after {took:.1f} s:\n{out.stdout[-6000:]}\n{out.stderr[-6000:]}")
    return out, took


def venv(name, python=sys.executable, system_site=True):
    path = os.path.join(WORK, name)
    shutil.rmtree(path, ignore_errors=True)
    run([python, "-m", "venv", *(["--system-site-packages"] if system_site else []), path])
    return os.path.join(path, "bin", "python")


def check(python):
    out, _ = run([python, CHECK], cwd=WORK)  # not the checkout: `import trnkit` must find the installed one
    print(out.stdout.strip())
    return out.stdout


PIP = ["-m", "pip", "--disable-pip-version-check", "--no-input", "--no-cache-dir"]
NO_NETWORK = ["--no-build-isolation", "--no-index"]


@pytest.fixture(scope="module", autouse=True)
def work():
    os.makedirs(WORK, exist_ok=True)


def test_pip_install_from_the_checkout():
    py = venv("venv-install")
    _, took = run([py, *PIP, "install", *NO_NETWORK, SOURCE], cwd=WORK)
    print(f"pip install . took {took:.1f} s")
    out, _ = run([py, *PIP, "show", "-f", "trnkit"])
    assert "Location: " + os.path.join(WORK, "venv-install") in out.stdout, out.stdout
    check(py)
    check_command(py)
    run([py, *PIP, "uninstall", "-y", "trnkit"])
    assert not glob.glob(os.path.join(WORK, "venv-install", "lib", "python3*", "site-packages", "trnkit"))


def check_command(py):
    """pip put the `trnkit` command in the venv's bin/ (issue 43): the CLI, with its libraries from
    the package, whatever the current folder."""
    command = os.path.join(os.path.dirname(py), "trnkit")
    assert os.access(command, os.X_OK), command
    out, _ = run([command, "--version"], cwd="/")
    assert out.stdout.startswith("trnkit "), out.stdout
    out, _ = run([command, "localize", "--print-config"], cwd="/")
    assert '"init_radius_m":50' in out.stdout.replace(" ", ""), out.stdout


def built_wheel():
    wheels = os.path.join(WORK, "wheels")
    shutil.rmtree(wheels, ignore_errors=True)
    _, took = run([sys.executable, *PIP, "wheel", *NO_NETWORK, "--no-deps", "-w", wheels, SOURCE], cwd=WORK)
    print(f"pip wheel . took {took:.1f} s")
    (wheel,) = glob.glob(os.path.join(wheels, "trnkit-*.whl"))
    return wheel


@pytest.fixture(scope="module")
def wheel():
    return built_wheel()


def test_pip_wheel_is_self_contained(wheel):
    tag = "cp%d%d-cp%d%d-linux_" % (sys.version_info[:2] * 2)
    assert tag in os.path.basename(wheel), wheel
    names = zipfile.ZipFile(wheel).namelist()
    for want in ["trnkit/__init__.py", "trnkit/__init__.pyi", "trnkit/py.typed", "trnkit/_backend.py", "trnkit/_energy.py"]:
        assert want in names, (want, names)
    assert any(n.startswith("trnkit/_trnkit.cpython-") for n in names), names
    assert any(n.startswith("trnkit/libtrnkit_core.so.") for n in names), names
    assert "trnkit/bin/trnkit" in names and "trnkit/_cli.py" in names, names
    meta = [n for n in names if n.endswith(".dist-info/METADATA")]
    text = zipfile.ZipFile(wheel).read(meta[0]).decode()
    assert "Requires-Dist: numpy" in text


def test_the_wheel_in_a_fresh_debian_venv(wheel):
    py = venv("venv-wheel")
    _, took = run([py, *PIP, "install", "--no-index", wheel])
    print(f"pip install trnkit.whl took {took:.1f} s")
    check(py)
    check_command(py)


def test_the_wheel_in_another_cpython_311(wheel, tmp_path):
    """A CPython 3.11 that is not Debian's (pyenv's builds its own libpython and headers): a venv
    of it without system packages, NumPy from Debian's python3-numpy (built for CPython 3.11)
    through a .pth file naming a folder that holds only numpy."""
    if not OTHER_PYTHON or not os.path.exists(OTHER_PYTHON):
        pytest.skip("NOT AVAILABLE: no CPython 3.11 besides Debian's (~/.pyenv/versions/3.11.*, or TRN_OTHER_PYTHON)")
    version = subprocess.run([OTHER_PYTHON, "-c", "import sys; print('%d.%d' % sys.version_info[:2])"], capture_output=True,
                             text=True, check=True).stdout.strip()
    if version != "%d.%d" % sys.version_info[:2]:
        pytest.skip(f"NOT AVAILABLE: {OTHER_PYTHON} is {version}, the wheel is for {sys.version_info[0]}.{sys.version_info[1]}")
    py = venv("venv-other", python=OTHER_PYTHON, system_site=False)
    only_numpy = os.path.join(WORK, "numpy-only")
    shutil.rmtree(only_numpy, ignore_errors=True)
    os.makedirs(only_numpy)
    import numpy
    os.symlink(os.path.dirname(numpy.__file__), os.path.join(only_numpy, "numpy"))
    site = subprocess.run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"], capture_output=True, text=True,
                          check=True).stdout.strip()
    with open(os.path.join(site, "debian-numpy.pth"), "w") as f:
        f.write(only_numpy + "\n")
    run([py, *PIP, "install", "--no-index", "--no-deps", wheel])
    out = check(py)
    assert os.path.realpath(OTHER_PYTHON).split("/bin/")[0] not in ("/usr",), OTHER_PYTHON
    assert "Python " + version in out
