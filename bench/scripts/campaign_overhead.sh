#!/bin/bash
# Per-point overhead of `asperity sweep`, before and after (issue 11, "Checks"): builds BASE's
# `asperity` in a temporary git worktree (Release, ccache, -j1), then runs bench/sweeps/overhead_1000.yaml
# (1,000 points of 1 ms on the stand-in P4.00N, one thread) PAIRS times with each binary,
# alternated, each into a fresh temporary store. Prints points/s of both, their ratio (median
# over the pairs), and whether both stores' points.csv agree byte for byte apart from wall_s.
# Usage: bench/scripts/campaign_overhead.sh BASE_COMMIT [PAIRS (default 3)]   (run from a built tree:
# build/asperity is the "after" binary)
set -euo pipefail
base=${1:?usage: bench/scripts/campaign_overhead.sh BASE_COMMIT [PAIRS]}
pairs=${2:-3}
root=$(cd "$(dirname "$0")/../.." && pwd)
after="$root/build/asperity"
campaign="$root/bench/sweeps/overhead_1000.yaml"
points=1000
[ -x "$after" ] || { echo "campaign_overhead: build $after first" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/asperity-overhead.XXXXXX")
cleanup() {
  git -C "$root" worktree remove --force "$work/base" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

git -C "$root" worktree add --detach --quiet "$work/base" "$base"
cmake -S "$work/base" -B "$work/base/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache >/dev/null
ninja -C "$work/base/build" -j1 asperity >/dev/null
before="$work/base/build/asperity"

wall() {  # wall seconds of one sweep with binary $1 into the fresh store $2
  local t0 t1
  t0=$(date +%s.%N)
  "$1" sweep "$campaign" -j 1 --quiet --out "$2"
  t1=$(date +%s.%N)
  echo "$t0 $t1" | awk '{printf "%.3f", $2 - $1}'
}
ratios=()
for ((i = 0; i < pairs; ++i)); do
  load=$(cut -d' ' -f1 /proc/loadavg)
  wb=$(wall "$before" "$work/before$i")
  wa=$(wall "$after" "$work/after$i")
  r=$(awk -v a="$wb" -v b="$wa" 'BEGIN {printf "%.3f", a / b}')
  ratios+=("$r")
  awk -v i="$i" -v a="$wb" -v b="$wa" -v r="$r" -v n="$points" -v l="$load" 'BEGIN {
    printf "pair %d (load %s): before %.2f s (%.0f points/s), after %.2f s (%.0f points/s), ratio %.2f\n",
           i, l, a, n / a, b, n / b, r }'
done
printf '%s\n' "${ratios[@]}" | sort -g | awk '{x[NR] = $1} END {
  m = NR % 2 ? x[(NR + 1) / 2] : (x[NR / 2] + x[NR / 2 + 1]) / 2
  printf "after/before speed over %d pairs: median %.2f, range %.2f-%.2f\n", NR, m, x[1], x[NR] }'
# The stores must hold the same rows: only the last column (wall_s) may differ.
strip() { sed 's/,[^,]*$//' "$1/points.csv"; }
if cmp -s <(strip "$work/before0") <(strip "$work/after0"); then
  echo "points.csv: identical apart from wall_s ($(wc -l <"$work/after0/points.csv") lines)"
else
  echo "points.csv: DIFFERENT apart from wall_s"; exit 1
fi
