#!/usr/bin/env bash
# ctest python_pip_install: `pip install .` and `pip install -e .` from a copy of the source tree (the files git tracks or
# would track) into a fresh venv (Debian's python3 with its site packages, no index, no isolation),
# reusing the CMake build BUILD_DIR for the compiled module; then imports it from outside the tree.
#   [PYTHON=/usr/bin/python3] tests/shell/test_pip_install.sh BUILD_DIR
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir "$tmp/clone"
(cd "$src" && git ls-files -co --exclude-standard -z | while IFS= read -r -d '' f; do
  [ -e "$f" ] && printf '%s\0' "$f"; done | xargs -0 cp --parents -t "$tmp/clone")
python=${PYTHON:-/usr/bin/python3}
# Without its own pip (ensurepip takes seconds): the system's pip installs into it (--python).
"$python" -m venv --without-pip --system-site-packages "$tmp/venv"
ASPERITY_CMAKE_BUILD_DIR="$build" "$python" -m pip --python "$tmp/venv/bin/python" install -q \
  --no-build-isolation --no-deps --no-index "$tmp/clone" >"$tmp/pip.log" 2>&1 || { cat "$tmp/pip.log"; exit 1; }
cd "$tmp"
env -u PYTHONPATH "$tmp/venv/bin/python" - "$tmp/venv" "$("$build/asperity" --version)" <<'PY'
import pathlib, sys
import asperity
venv, version_line = sys.argv[1], sys.argv[2]
where = pathlib.Path(asperity.__file__).resolve()
assert str(where).startswith(str(pathlib.Path(venv).resolve())), where  # the installed copy
assert version_line.startswith(f"asperity {asperity.__version__} ("), (version_line, asperity.__version__)
assert (where.parent / "__init__.pyi").exists() and (where.parent / "py.typed").exists()
assert asperity.units("Q_s") == "N"
print("installed", asperity.__version__, "at", where.parent)
PY
# `pip install -e .`: the package imported from the clone's source folder, the compiled module
# beside it, so an edit of a .py file shows at the next import.
"$python" -m venv --without-pip --system-site-packages "$tmp/venv-e"
ASPERITY_CMAKE_BUILD_DIR="$build" "$python" -m pip --python "$tmp/venv-e/bin/python" install -q \
  --no-build-isolation --no-deps --no-index -e "$tmp/clone" >"$tmp/pip-e.log" 2>&1 || { cat "$tmp/pip-e.log"; exit 1; }
echo 'EDITED = "yes"' >>"$tmp/clone/src/python/asperity/plot.py"
env -u PYTHONPATH "$tmp/venv-e/bin/python" - "$tmp/clone" <<'PY'
import pathlib, sys
import asperity, asperity.plot
where = pathlib.Path(asperity.__file__).resolve()
assert where.parent == (pathlib.Path(sys.argv[1]) / "src" / "python" / "asperity").resolve(), where
assert asperity.plot.EDITED == "yes"  # the source itself, not a copy
assert asperity.units("Q_s") == "N" and asperity.run  # the compiled module loads
print("editable install at", where.parent)
PY
