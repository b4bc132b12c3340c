"""Builds the Python package for `pip install .` with the project's CMake (see pyproject.toml).

The compiled module and the command-line binary (shipped as asperity/bin/asperity, run by the
`asperity` command: asperity/_cli.py) come from a CMake build folder: $ASPERITY_CMAKE_BUILD_DIR
when set (a build already configured, reused as is); else build/ when it is a Release build for
this interpreter (the developer's build, brought up to date: seconds); else build/pip, configured
Release for this interpreter on first use. A line on stderr names the folder and why; the build's
own steps follow (pip shows both with -v). CMAKE_BUILD_PARALLEL_LEVEL sets the number of jobs.
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


def cmake_cache(build):
    """The entries NAME -> value of build/CMakeCache.txt ({} when the folder is not configured)."""
    try:
        text = (build / "CMakeCache.txt").read_text()
    except OSError:
        return {}
    return dict(re.findall(r"^([A-Za-z_][\w.+-]*):[A-Z]+=(.*)$", text, re.M))


def unfit_for_this_python(cache):
    """Why a configured build folder cannot give this interpreter its module, or "" when it can:
    a Release build of the module (no sanitizer) for the same interpreter, a venv of it included."""
    if not cache:
        return "not configured"
    if cache.get("CMAKE_BUILD_TYPE") != "Release":
        return f"a {cache.get('CMAKE_BUILD_TYPE') or 'no-type'} build, not Release"
    if cache.get("ASPERITY_SANITIZE", "OFF").upper() in ("ON", "TRUE", "1", "YES"):
        return "a sanitizer build"
    built_for = cache.get("ASPERITY_PYTHON_EXECUTABLE")
    if not built_for:
        return "no Python module configured"
    this = os.path.realpath(getattr(sys, "_base_executable", None) or sys.executable)
    if os.path.realpath(built_for) != this:
        return f"configured for {built_for}, not {sys.executable}"
    return ""


def build_folder():
    """The CMake build folder to build in, and the line that says which and why."""
    chosen = os.environ.get("ASPERITY_CMAKE_BUILD_DIR")
    if chosen:
        return pathlib.Path(chosen).resolve(), f"building in {chosen} (ASPERITY_CMAKE_BUILD_DIR)"
    build = ROOT / "build"
    why = unfit_for_this_python(cmake_cache(build))
    if not why:
        return build, (f"reusing the build folder {build} (Release, for this interpreter); "
                       "ASPERITY_CMAKE_BUILD_DIR names another")
    return build / "pip", (f"building in {build / 'pip'} ({build}: {why}); a first build takes minutes, "
                           "pip install -v shows its steps")


class CMakeBuildPy(build_py):
    """build_py, plus the compiled _asperity and the command-line binary from the CMake build."""

    def run(self):
        super().run()
        build, line = build_folder()
        print(f"setup.py: {line}", file=sys.stderr, flush=True)
        if not (build / "CMakeCache.txt").exists():
            subprocess.check_call(["cmake", "-S", str(ROOT), "-B", str(build), "-G", "Ninja",
                                   "-DCMAKE_BUILD_TYPE=Release", f"-DPython3_EXECUTABLE={sys.executable}"])
        subprocess.check_call(["cmake", "--build", str(build), "--target", "_asperity", "asperity"])
        # A build folder configured for another interpreter would give a module this one cannot load.
        module = build / "python" / "asperity" / ("_asperity" + sysconfig.get_config_var("EXT_SUFFIX"))
        if not module.exists():
            sys.exit(f"setup.py: {module} not built (is {build} configured for {sys.executable}?)")
        binary = build / "asperity"
        # `pip install -e .` imports the package from src/python/asperity itself (setuptools maps
        # the source folder), so the compiled files go there too (ignored by git), as
        # `build_ext --inplace` would put them; rerun `pip install -e .` after a rebuild.
        targets = [pathlib.Path(self.build_lib) / "asperity"]
        if getattr(self, "editable_mode", False):
            targets.append(ROOT / "src" / "python" / "asperity")
        for target in targets:
            (target / "bin").mkdir(parents=True, exist_ok=True)
            shutil.copy2(module, target / module.name)
            shutil.copy2(binary, target / "bin" / "asperity")


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
    # Relative to this folder (pip runs setup.py in it), so that SOURCES.txt of the egg-info lists
    # relative paths: absolute ones from another clone sharing build/ would fail its check.
    options={"build": {"build_base": "build/setuptools"}, "egg_info": {"egg_base": "build"}},
)
