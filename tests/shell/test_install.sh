#!/bin/bash
# Installs a build tree into a fresh prefix and builds and runs a stranger's CMake project
# (tests/consumer) against it with find_package(asperity); runs the installed executable.
#   tests/shell/test_install.sh BUILD_DIR
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(realpath "$1")
w=$(mktemp -d -t asperity-install.XXXXXX)
trap 'rm -rf "$w"' EXIT
cmake --install "$build" --prefix "$w/prefix" > "$w/install.log"
"$w/prefix/bin/asperity" --version
cmake -S "$root/tests/consumer" -B "$w/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$w/prefix" > "$w/configure.log" || { cat "$w/configure.log"; exit 1; }
cmake --build "$w/build" -j 2 > "$w/build.log" || { cat "$w/build.log"; exit 1; }
"$w/build/consumer" "$root/scenes/paper/P4.00N.yaml"
# The Python package from the install tree (when the build has it).
pkg=$(find "$w/prefix" -path '*/dist-packages/asperity/__init__.py' | head -n 1)
if [ -n "$pkg" ]; then
  PYTHONPATH=$(dirname "$(dirname "$pkg")") /usr/bin/python3 -c \
    "import asperity; print('python: import asperity from', asperity.__file__.replace('$w', 'PREFIX'), '->', asperity.version())"
fi
