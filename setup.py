"""Builds the Python package for `pip install .` with the project's CMake (see pyproject.toml).

The compiled module comes from a CMake build folder: $ASPERITY_CMAKE_BUILD_DIR when set (a build
already configured, e.g. the developer's build/, reused as is), else build/pip, configured Release
for this interpreter on first use. CMAKE_BUILD_PARALLEL_LEVEL sets the number of jobs.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Distribution, setup
from setuptools.command.build_py import build_py

ROOT = pathlib.Path(__file__).resolve().parent


def version():
    """The one version number: CMakeLists.txt's project(... VERSION x.y.z)."""
    return re.search(r"project\(asperity VERSION (\S+)", (ROOT / "CMakeLists.txt").read_text()).group(1)


class CMakeBuildPy(build_py):
    """build_py, plus the compiled _asperity from the CMake build."""

    def run(self):
        super().run()
        build = pathlib.Path(os.environ.get("ASPERITY_CMAKE_BUILD_DIR") or ROOT / "build" / "pip").resolve()
        if not (build / "CMakeCache.txt").exists():
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja",
                                   "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_asperity"])
        # A build folder configured for another interpreter would give a module this one cannot load.
        module = build / "python" / "asperity" / ("_asperity" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not module.exists():
            sys.exit(f"setup.py: {module} not built (is {build} configured for {sys.executable}?)")
        target = pathlib.Path(self.build_lib) / "asperity"
        target.mkdir(parents=True, exist_ok=True)
        shutil.copy2(module, target / module.name)
        # `pip install -e .` imports the package from src/python/asperity itself (setuptools maps
        # the source folder), so the compiled module goes there too (ignored by git), as
        # `build_ext --inplace` would put it; rerun `pip install -e .` after a rebuild.
        if getattr(self, "editable_mode", False):
            shutil.copy2(module, ROOT / "src" / "python" / "asperity" / module.name)


class BinaryDistribution(Distribution):
    """A wheel tagged for this platform and interpreter: it holds a compiled module."""

    def has_ext_modules(self):
        return True


setup(
    version=version(),
    packages=["asperity"],
    package_dir={"asperity": "src/python/asperity"},
    package_data={"asperity": ["*.pyi", "py.typed"]},
    cmdclass={"build_py": CMakeBuildPy},
    distclass=BinaryDistribution,
    # Out of the source tree's top: CMake's build/ is where setuptools would write otherwise.
    options={"build": {"build_base": str(ROOT / "build" / "setuptools")},
             "egg_info": {"egg_base": str(ROOT / "build")}},
)
