"""The build backend of pyproject.toml: setuptools' own (setuptools.build_meta, which runs
setup.py), once the interpreter that runs it is known to have what that backend needs.

Without this check, `pip install --no-build-isolation .` under an interpreter that lacks the
wheel package stops deep in setuptools at "error: invalid command 'bdist_wheel'", and one that
lacks setuptools at "Cannot import 'setuptools.build_meta'"; neither names the interpreter (often
another python3 earlier on PATH than the one meant). This prints one line that does, and exits 1.
"""
import importlib.util
import sys

# What the build needs, with the Debian package that provides it for /usr/bin/python3.
_NEEDS = (("setuptools", "python3-setuptools"), ("wheel", "python3-wheel"))


def _has(name):
    """Whether `name` can be imported: setuptools from 70.1 on has bdist_wheel without wheel."""
    if importlib.util.find_spec(name) is not None:
        return True
    return (name == "wheel" and importlib.util.find_spec("setuptools") is not None
            and importlib.util.find_spec("setuptools.command.bdist_wheel") is not None)


def _missing():
    return [(name, deb) for name, deb in _NEEDS if not _has(name)]


def _message(missing):
    names = " and ".join(f"'{name}'" for name, _ in missing)
    debs = " ".join(deb for _, deb in missing)
    packages = "packages" if len(missing) > 1 else "package"
    return (f"asperity: {sys.executable} cannot build the package: it lacks the Python {packages} {names} "
            f"(Debian: apt install {debs} and make the venv from /usr/bin/python3 with --system-site-packages; "
            f"another interpreter: {sys.executable} -m pip install {' '.join(name for name, _ in missing)})")


if _missing():
    sys.exit(_message(_missing()))

from setuptools.build_meta import *  # noqa: E402,F401,F403  (the hooks pip calls)
from setuptools.build_meta import __all__  # noqa: E402,F401
