"""Builds the gjkdem Python module with CMake for pip (pyproject.toml).

The extension gjkdem._core is the CMake target gjkdem_python, configured in
build/pip (Release, without tests, benchmarks or examples) unless
GJKDEM_BUILD_DIR names a build tree already configured with the module
(build.sh's build/, whose objects are then reused). Nothing is downloaded:
CMake finds Debian's pybind11 and the libraries build.sh installs.
"""
import os
import pathlib
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        given = os.environ.get("GJKDEM_BUILD_DIR")
        build = pathlib.Path(given).resolve() if given else ROOT / "build" / "pip"
        if not (build / "CMakeCache.txt").exists():
            build.mkdir(parents=True, exist_ok=True)
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build), "-DCMAKE_BUILD_TYPE=Release",
                                   f"-DPython_EXECUTABLE={sys.executable}", "-DGJKDEM_BUILD_TESTS=OFF",
                                   "-DGJKDEM_BUILD_BENCH=OFF", "-DGJKDEM_BUILD_EXAMPLES=OFF",
                                   "-DGJKDEM_BUILD_APPS=OFF"])
        jobs = str(os.cpu_count() or 1)
        subprocess.check_call(["cmake", "--build", str(build), "--target", "gjkdem_python", "-j", jobs])
        built = sorted((build / "python" / "gjkdem").glob("_core*.so"))
        if not built:
            raise RuntimeError(f"CMake built no gjkdem/_core module in {build} (is pybind11-dev installed?)")
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built[-1], target)


setup(
    packages=["gjkdem"],
    package_dir={"gjkdem": "python/gjkdem"},
    ext_modules=[Extension("gjkdem._core", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": "build/setuptools"}, "egg_info": {"egg_base": "build"}},
)
