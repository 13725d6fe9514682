"""`pip install .` and `pip wheel .` (docs/python.md): the package `metrosync` (tools/python/
metrosync) with its C++ core `_metrosync` built by this repository's CMake, linking the system's
libraries (Debian 12: Simbody, Ceres, yaml-cpp, pybind11-dev). Offline, with Debian's setuptools:

    python3 -m pip install --no-build-isolation .

The CMake build goes into build-pip/cmake (or METROSYNC_CMAKE_BUILD_DIR: an existing build tree
of this checkout, e.g. build, whose module is then only brought up to date); setuptools' own
files into build-pip (or METROSYNC_BUILD_BASE)."""

import os
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = os.path.dirname(os.path.abspath(__file__))
BUILD_BASE = os.environ.get("METROSYNC_BUILD_BASE") or os.path.join(ROOT, "build-pip")


def cmake_configure(build_dir):
    """A Release build tree of this checkout for the running interpreter (ccache when found)."""
    args = ["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
            "-DPython_EXECUTABLE=" + sys.executable]
    if shutil.which("ccache"):
        args.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
    subprocess.run(args, check=True)


class CMakeBuild(build_ext):
    """Builds the CMake target _metrosync and puts the module where setuptools wants it."""

    def build_extension(self, ext):
        build_dir = os.environ.get("METROSYNC_CMAKE_BUILD_DIR") or os.path.join(BUILD_BASE,
                                                                                "cmake")
        build_dir = os.path.abspath(build_dir)
        if not os.path.exists(os.path.join(build_dir, "CMakeCache.txt")):
            cmake_configure(build_dir)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", build_dir, "--target", "_metrosync", "-j", jobs],
                       check=True)
        name = "_metrosync" + sysconfig.get_config_var("EXT_SUFFIX")
        built = os.path.join(build_dir, "python", "metrosync", name)
        if not os.path.exists(built):
            sys.exit("metrosync: %s has no %s (a module for another Python? configure it with "
                     "-DPython_EXECUTABLE=%s)" % (build_dir, name, sys.executable))
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)


setup(
    packages=["metrosync"],
    package_dir={"metrosync": "tools/python/metrosync"},
    package_data={"metrosync": ["*.pyi", "py.typed"]},
    ext_modules=[Extension("metrosync._metrosync", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": BUILD_BASE},
             "egg_info": {"egg_base": BUILD_BASE}},
)
