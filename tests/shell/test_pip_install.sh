#!/usr/bin/env bash
# ctest python_pip_install: docs/python.md's install, as a user runs it. `pip install .` and
# `pip install -e .` from a copy of the source tree (the files git tracks or would track) into a
# fresh venv (Debian's python3 with its site packages, no index, no isolation), reusing the CMake
# build BUILD_DIR for the compiled module and the command line; then, from outside the tree: the
# package imports, the venv's `asperity` command is build/asperity (output and exit status), and
# after the documented `python -m ipykernel install --sys-prefix` nbclient runs
# examples/calibrate_one_load.ipynb in the notebook's own kernel (python3), which must be the venv's.
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
# The clone's build/ is BUILD_DIR (a link), as a developer's clone with its build: a Release build
# for this interpreter is reused without being named, and pip -v shows the line that says so.
if grep -qx 'CMAKE_BUILD_TYPE:STRING=Release' "$build/CMakeCache.txt"; then
  ln -s "$build" "$tmp/clone/build"
  reuse="setup.py: reusing the build folder $tmp/clone/build (Release, for this interpreter)"
else  # another build type is not reused (it would build build/pip from scratch): name it
  export ASPERITY_CMAKE_BUILD_DIR="$build"
  reuse="setup.py: building in $build (ASPERITY_CMAKE_BUILD_DIR)"
fi
"$python" -m pip --python "$tmp/venv/bin/python" install -v \
  --no-build-isolation --no-deps --no-index "$tmp/clone" >"$tmp/pip.log" 2>&1 || { cat "$tmp/pip.log"; exit 1; }
grep -qF "$reuse" "$tmp/pip.log" || { cat "$tmp/pip.log"; echo "no line '$reuse'"; exit 1; }
unset ASPERITY_CMAKE_BUILD_DIR
# An interpreter without setuptools and wheel (a venv without the system's packages): pip stops
# before any build at the backend's one line, which names the interpreter and what it lacks.
"$python" -m venv --without-pip "$tmp/bare"
rc=0; "$python" -m pip --python "$tmp/bare/bin/python" install --no-build-isolation --no-deps --no-index \
  "$tmp/clone" >"$tmp/bare.log" 2>&1 || rc=$?
grep -qF "asperity: $tmp/bare/bin/python cannot build the package: it lacks the Python packages 'setuptools' and 'wheel' (Debian: apt install python3-setuptools python3-wheel" "$tmp/bare.log" \
  && [ "$rc" != 0 ] || { cat "$tmp/bare.log"; echo "no one-line error naming the interpreter (exit $rc)"; exit 1; }
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
# The venv's `asperity` command: the same output and exit status as build/asperity.
[ "$(env -u PYTHONPATH "$tmp/venv/bin/asperity" --version)" = "$("$build/asperity" --version)" ] \
  || { echo "venv asperity --version differs from build/asperity's"; exit 1; }
rc=0; env -u PYTHONPATH "$tmp/venv/bin/asperity" run "$tmp/nonexistent.yaml" 2>"$tmp/venv.err" || rc=$?
want=0; "$build/asperity" run "$tmp/nonexistent.yaml" 2>"$tmp/build.err" || want=$?
[ "$rc" = 2 ] && [ "$want" = 2 ] || { echo "asperity run of a missing scene: exit $rc (venv), $want (build), not 2"; exit 1; }
cmp "$tmp/venv.err" "$tmp/build.err" || { echo "stderr differs"; cat "$tmp/venv.err" "$tmp/build.err"; exit 1; }
echo "venv asperity: $(cat "$tmp/venv.err")"
# The notebook in the venv's kernel: the documented command, then the notebook's own kernel name
# (python3), found as Jupyter started by the venv's interpreter finds it (JUPYTER_DATA_DIR: no
# kernel of this user's in the way). Debian's python3 kernel (/usr/bin/python3) has no asperity.
export JUPYTER_DATA_DIR="$tmp/jupyter" JUPYTER_RUNTIME_DIR="$tmp/jupyter/runtime" IPYTHONDIR="$tmp/ipython"
export MPLBACKEND=Agg PYDEVD_DISABLE_FILE_VALIDATION=1
env -u PYTHONPATH "$tmp/venv/bin/python" -m ipykernel install --sys-prefix >"$tmp/kernel.log" 2>&1 \
  || { cat "$tmp/kernel.log"; exit 1; }
env -u PYTHONPATH "$tmp/venv/bin/python" - "$tmp/venv" "$tmp/clone/examples/calibrate_one_load.ipynb" <<'PY'
import pathlib, sys
import nbclient, nbformat
venv, path = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2])
nb = nbformat.read(path, as_version=4)
assert nb.metadata.kernelspec.name == "python3"
nb.cells.append(nbformat.v4.new_code_cell("import sys, asperity\nprint('kernel:', sys.prefix, asperity.__file__)"))
nbclient.NotebookClient(nb, timeout=120, resources={"metadata": {"path": str(path.parent)}}).execute()
text = "".join(o.get("text", "") for c in nb.cells if c.cell_type == "code" for o in c.outputs)
assert "fitted alpha_b = " in text, text
prefix, module = text.split("kernel: ")[1].split()
assert pathlib.Path(prefix).resolve() == venv, (prefix, venv)  # the venv's interpreter
assert pathlib.Path(module).resolve().is_relative_to(venv), module  # and its installed package
print("notebook ran in the venv's kernel:", prefix)
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
[ "$(env -u PYTHONPATH "$tmp/venv-e/bin/asperity" --version)" = "$("$build/asperity" --version)" ] \
  || { echo "editable install: asperity --version differs from build/asperity's"; exit 1; }
