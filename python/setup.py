"""Installs the rrlab package: setup.py builds the engine module (_rrlab) with
CMake, in the project's Release build directory (../build, or the directory
RRLAB_BUILD_DIR names), then installs it with the pure-Python files of
python/rrlab, its stubs (_rrlab.pyi) and py.typed. The metadata is
pyproject.toml's [project] table. numpy comes from Debian (python3-numpy);
nothing is downloaded.

    pip install --no-build-isolation ./python
"""
import importlib.util
import os
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def project_version():
    """The project(rrlab VERSION x.y.z) of CMakeLists.txt, which `rrlab --version` prints too."""
    with open(os.path.join(ROOT, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"project\(rrlab VERSION ([0-9.]+)", f.read()).group(1)


def package_version():
    """The [project] version of pyproject.toml (the metadata pip installs)."""
    with open(os.path.join(HERE, "pyproject.toml"), encoding="utf-8") as f:
        return re.search(r'^version = "([^"]+)"', f.read(), re.M).group(1)


# before anything else (pip runs this file first to read the metadata): the
# engine's arrays need numpy, which Debian installs for /usr/bin/python3 only
if importlib.util.find_spec("numpy") is None:
    sys.exit(f"rrlab: {sys.executable} has no numpy. Debian's python3-numpy (scripts/install-deps) serves "
             "/usr/bin/python3: install with it, or in a venv made by "
             "/usr/bin/python3 -m venv --system-site-packages (docs/python.md)")


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
        module = "_rrlab" + sysconfig.get_config_var("EXT_SUFFIX")  # the name this Python imports
        if not os.path.exists(os.path.join(built, module)):
            found = [name for name in os.listdir(built) if name.startswith("_rrlab")] if os.path.isdir(built) else []
            sys.exit(f"rrlab: no {module} in {built} (found: {', '.join(found) or 'none'}). "
                     + ("That build is for another Python: install with the Python it was configured for, "
                        "or set RRLAB_BUILD_DIR to a new directory." if found else
                        "Is pybind11-dev installed (scripts/install-deps)?"))
        shutil.copy2(os.path.join(built, module), os.path.join(self.build_lib, "rrlab", module))


class EngineDistribution(Distribution):
    def has_ext_modules(self):
        return True  # a wheel for this platform and Python: it holds a compiled module


# the metadata is pyproject.toml's [project] table; its version must be the
# engine's, which rrlab.__version__ reports
if package_version() != project_version():
    sys.exit(f"rrlab: python/pyproject.toml says version {package_version()}, CMakeLists.txt {project_version()}: "
             "make them one")

setup(cmdclass={"build_py": BuildWithEngine}, distclass=EngineDistribution)
