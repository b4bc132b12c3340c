#!/usr/bin/env bash
# The objective's landscape (docs/calibration.md, "The objective's landscape"): a SYNTHETIC
# experiment (examples/landscape/recipe.yaml), then 1-D profiles of the joint objective through
# its truth under each Q(t) score (examples/landscape/*.yaml); one table and one figure.
#   scripts/landscape.sh [OUT]     (default results/landscape; a new folder or one it made)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-results/landscape}"
if [ -L "$out" ]; then echo "landscape.sh: $out: a symbolic link; give a plain folder" >&2; exit 2; fi
if [ -e "$out" ] && [ ! -e "$out/.landscape" ]; then
  echo "landscape.sh: $out: exists and was not made by this script; give a new folder" >&2
  exit 2
fi
mkdir -p "$out"
touch "$out/.landscape"
rm -rf "$out/work"
build/asperity generate --recipe examples/landscape/recipe.yaml --out "$out/work/syn"
for score in pointwise loading_and_cycles; do
  cp "examples/landscape/$score.yaml" "$out/work/syn/"
  build/asperity fit "$out/work/syn/$score.yaml" --out "$out/work/$score" -j 2
done
python3 bench/scripts/landscape_table.py "$out/work" "$out/landscape.csv"
repo="$(pwd)"
(cd "$out" && gnuplot "$repo/bench/scripts/landscape.gp")  # fixed names there: no path text reaches gnuplot
echo "landscape.sh: wrote $out/landscape.csv and $out/landscape.png"
