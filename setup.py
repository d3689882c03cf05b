"""`pip install .` of the Python package `certcyl`, offline with Debian's tooling:

    /usr/bin/python3 -m pip install --no-build-isolation --no-deps --no-index .

(add `--break-system-packages` for a system install, or install into a virtual environment
created with `--system-site-packages`, or `--target DIR`). The compiled module is built by CMake
(the target certcyl_python of python/CMakeLists.txt, which needs the Debian packages of
scripts/install-deps.sh); setuptools only packages it with python/certcyl/__init__.py. The
metadata is in pyproject.toml.

Environment: CERTCYL_PIP_BUILD_DIR, setuptools' build folder (default build-pip/ in the
checkout; the CMake build is its cmake/ folder, kept between runs so a second install rebuilds
only what changed); CMAKE_ARGS, more CMake options (e.g. -DCERTCYL_WERROR=ON to reuse ccache's
objects of a build with those flags); CMAKE_BUILD_PARALLEL_LEVEL, the build's jobs (default:
every core).
"""
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD = Path(os.environ.get("CERTCYL_PIP_BUILD_DIR") or ROOT / "build-pip").resolve()


class CMakeExtension(Extension):
    """The module certcyl._certcyl, built by CMake rather than by setuptools."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        cmake_dir = BUILD / "cmake"
        configure = ["cmake", "-S", str(ROOT), "-B", str(cmake_dir), "-DCMAKE_BUILD_TYPE=Release",
                     f"-DPython3_EXECUTABLE={sys.executable}", "-DCERTCYL_BUILD_TESTS=OFF",
                     "-DCERTCYL_BUILD_BENCHMARKS=OFF", "-DCERTCYL_BUILD_EXPERIMENTS=OFF"]
        configure += shlex.split(os.environ.get("CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(cmake_dir), "--target", "certcyl_python", "-j", jobs], check=True)
        built = sorted((cmake_dir / "python" / "certcyl").glob("_certcyl*.so"))
        if len(built) != 1:
            raise RuntimeError(f"expected one compiled module in {cmake_dir / 'python' / 'certcyl'}, found {built}")
        target = Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[0], target)


BUILD.mkdir(parents=True, exist_ok=True)
setup(
    packages=["certcyl"],
    package_dir={"certcyl": "python/certcyl"},
    ext_modules=[CMakeExtension("certcyl._certcyl")],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(BUILD)}, "egg_info": {"egg_base": str(BUILD)}},
    zip_safe=False,
)
