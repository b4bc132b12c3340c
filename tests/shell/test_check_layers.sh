#!/usr/bin/env bash
# ctest: scripts/check_layers.py passes a tree that keeps the layers of src/layers.txt and fails
# (exit 1, naming FILE:LINE) once a lower layer includes a higher one.
# Usage: tests/shell/test_check_layers.sh PYTHON CHECKER
set -u
python=$1 checker=$2
here=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d) && trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/src/io" "$tmp/src/observe" "$tmp/src/report"
cp "$here/src/layers.txt" "$tmp/src/"
printf '#pragma once\n#include <string>\n' > "$tmp/src/io/text.hpp"
printf '#pragma once\n#include "io/text.hpp"\n' > "$tmp/src/observe/series.hpp"
printf '#include "observe/series.hpp"\n#include "io/text.hpp"\n#include "plot.hpp"\n' > "$tmp/src/report/plot.cpp"

out=$("$python" "$checker" "$tmp/src"); rc=$?
[ $rc -eq 0 ] || { echo "FAIL: clean tree gave exit $rc:"; echo "$out"; exit 1; }

# The planted offence: observe (layer 4) includes report (layer 6) on line 4.
printf '// a plot from the observables\n#include "report/plot.hpp"\n' >> "$tmp/src/observe/series.hpp"
out=$("$python" "$checker" "$tmp/src"); rc=$?
[ $rc -eq 1 ] || { echo "FAIL: upward include gave exit $rc (want 1):"; echo "$out"; exit 1; }
echo "$out" | grep -qF "$tmp/src/observe/series.hpp:4: includes report/plot.hpp (layer observe -> report)" ||
  { echo "FAIL: the offending FILE:LINE is not named:"; echo "$out"; exit 1; }

# A folder on no layer is an error too.
sed -i '/report\/plot.hpp/d' "$tmp/src/observe/series.hpp"
mkdir -p "$tmp/src/extra" && printf '\n' > "$tmp/src/extra/x.hpp"
out=$("$python" "$checker" "$tmp/src"); rc=$?
[ $rc -eq 1 ] && echo "$out" | grep -qF "$tmp/src/extra/: folder on no layer" ||
  { echo "FAIL: an unplaced folder passed (exit $rc):"; echo "$out"; exit 1; }
echo "ok: clean tree passes; upward include and unplaced folder fail"
