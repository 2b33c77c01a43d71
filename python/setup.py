"""Installs the rrlab package: setup.py builds the engine module (_rrlab) with
CMake, in the project's Release build directory (../build, or the directory
RRLAB_BUILD_DIR names), then installs it with the pure-Python files of
python/rrlab. numpy comes from Debian (python3-numpy); nothing is downloaded.

    pip install --no-build-isolation ./python
"""
import os
import re
import shutil
import subprocess
import sys

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def project_version():
    """The project(rrlab VERSION x.y.z) of CMakeLists.txt, which `rrlab --version` prints too."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(rrlab VERSION ([0-9.]+)", f.read()).group(1)


class BuildWithEngine(build_py):
    """build_py, plus the engine module built by CMake for this interpreter."""

    def run(self):
        build = os.path.abspath(os.environ.get("RRLAB_BUILD_DIR", os.path.join(ROOT, "build")))
        if not os.path.exists(os.path.join(build, "CMakeCache.txt")):
            subprocess.check_call(["cmake", "-S", ROOT, "-B", build, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                                   f"-DRRLAB_PYTHON3={sys.executable}"])
        subprocess.check_call(["cmake", "--build", build, "--target", "rrlab_python"])
        super().run()
        built = os.path.join(build, "python", "rrlab")
        modules = [name for name in os.listdir(built) if name.startswith("_rrlab") and name.endswith(".so")]
        if not modules:
            sys.exit(f"rrlab: no engine module in {built}: is pybind11-dev installed (scripts/install-deps)?")
        for name in modules:
            shutil.copy2(os.path.join(built, name), os.path.join(self.build_lib, "rrlab", name))


class EngineDistribution(Distribution):
    def has_ext_modules(self):
        return True  # a wheel for this platform and Python: it holds a compiled module


setup(
    name="rrlab",
    version=project_version(),
    description="Redundancy-resolution lab: the engine in-process, methods in Python, the REST client",
    packages=["rrlab"],
    python_requires=">=3.9",
    cmdclass={"build_py": BuildWithEngine},
    distclass=EngineDistribution,
    zip_safe=False,
)
