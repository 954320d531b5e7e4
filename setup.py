"""setuptools' half of `pip install .` (pyproject.toml has the metadata): the extension
trnkit._trnkit is built by CMake, with the libtrnkit_* shared libraries it loads copied beside it
(RUNPATH $ORIGIN), so the installed package needs nothing from the checkout.

Environment:
  TRNKIT_CMAKE_BUILD_DIR      the CMake tree (default: build-pip/ in the checkout, kept between runs)
  TRN_REQUIRE_BACKENDS        families the build must have (default "opencl;vulkan", as ./run test;
                              empty: build with whatever CMake finds)
  TRNKIT_CMAKE_ARGS           extra CMake configure arguments (split on spaces)
  CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default: CMake's)
"""
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent


def version():
    m = re.search(r"project\(trnkit VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not m:
        raise RuntimeError("no `project(trnkit VERSION x.y.z` in CMakeLists.txt")
    return m.group(1)


class CMakeBuild(build_ext):
    """Configures a CMake tree for this interpreter with TRN_PYTHON_WHEEL=ON, builds the targets
    trnkit_python and trnkit_cli (and so only the libraries they link), installs the `python` component to a
    staging folder, checks the backends it has, and copies the compiled files into the package."""

    def run(self):
        for ext in self.extensions:
            self.build_cmake(ext)

    def build_cmake(self, ext):
        tree = Path(os.environ.get("TRNKIT_CMAKE_BUILD_DIR") or ROOT / "build-pip").resolve()
        stage = Path(self.build_temp).resolve() / "stage"
        configure = ["cmake", "-S", str(ROOT), "-B", str(tree), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython3_EXECUTABLE={sys.executable}", "-DTRN_PYTHON_WHEEL=ON", "-DTRN_PYTHON_INSTALL_DIR=.",
                     "-DTRN_BUILD_TESTS=OFF", "-DTRN_BUILD_BENCH=OFF"]
        if not (tree / "CMakeCache.txt").exists() and shutil.which("ninja"):
            configure += ["-G", "Ninja"]
        configure += os.environ.get("TRNKIT_CMAKE_ARGS", "").split()
        self.spawn(configure)
        self.spawn(["cmake", "--build", str(tree), "--target", "trnkit_python", "trnkit_cli"])
        shutil.rmtree(stage, ignore_errors=True)
        self.spawn(["cmake", "--install", str(tree), "--component", "python", "--prefix", str(stage)])
        self.check_backends(stage)

        target = Path(self.get_ext_fullpath(ext.name))
        built = stage / "trnkit" / target.name
        if not built.exists():
            found = sorted(p.name for p in (stage / "trnkit").glob("_trnkit*"))
            raise RuntimeError(f"CMake built {found}, not {target.name} for {sys.executable} (EXT_SUFFIX mismatch)")
        target.parent.mkdir(parents=True, exist_ok=True)
        for f in sorted((stage / "trnkit").iterdir()):
            if f.name.endswith(".so") or ".so." in f.name:
                shutil.copyfile(f, target.parent / f.name)
                print(f"trnkit: {target.parent / f.name}")
        # The CLI, which the `trnkit` console script runs (python/trnkit/_cli.py): executable kept.
        (target.parent / "bin").mkdir(exist_ok=True)
        shutil.copy2(stage / "trnkit" / "bin" / "trnkit", target.parent / "bin" / "trnkit")
        print(f"trnkit: {target.parent / 'bin' / 'trnkit'}")

    def check_backends(self, stage):
        """A wheel without the backends asked for is refused, not built quietly without them."""
        probe = "import trnkit; print(' '.join(trnkit.families()))"
        env = dict(os.environ, PYTHONPATH=str(stage), PYTHONNOUSERSITE="1", PYTHONDONTWRITEBYTECODE="1")
        out = subprocess.run([sys.executable, "-c", probe], env=env, cwd=str(stage), capture_output=True, text=True)
        if out.returncode != 0:
            raise RuntimeError(f"the built trnkit does not import with {sys.executable}:\n{out.stderr}")
        have = out.stdout.split()
        required = [f for f in os.environ.get("TRN_REQUIRE_BACKENDS", "opencl;vulkan").replace(",", ";").split(";") if f]
        missing = [f for f in required if f not in have]
        print(f"trnkit: backends built: {', '.join(have)}")
        if missing:
            raise RuntimeError(f"trnkit was built without the {' and '.join(missing)} backend(s) (CMake did not find their "
                               "development packages: scripts/install-deps.sh); TRN_REQUIRE_BACKENDS= pip install ... "
                               f"accepts a wheel with only {', '.join(have)}")


(ROOT / "build-pip").mkdir(exist_ok=True)
setup(
    version=version(),
    ext_modules=[Extension("trnkit._trnkit", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    # setuptools' own build folders beside the CMake tree, not in the project's build/
    options={"build": {"build_base": "build-pip/setuptools"}, "egg_info": {"egg_base": "build-pip"}},
    zip_safe=False,
)
