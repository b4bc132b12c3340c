#!/bin/bash
# Parallel efficiency of `asperity sweep` (README figure): PAIRS alternated runs of
# bench/sweeps/bench_threads.yaml (40 points on the stand-in P2.07N) with 1 and with 2 threads, each into
# a fresh temporary store. Prints per pair the wall times, points/s and efficiency
# = (points/s at 2 threads) / (2 × points/s at 1 thread), then the median and range.
# Usage: bench/scripts/sweep_efficiency.sh [PAIRS (default 5)]
set -euo pipefail
pairs=${1:-5}
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/asperity-eff.XXXXXX")
trap 'rm -rf "$work"' EXIT
points=40
wall() {  # wall seconds of one sweep into a fresh store
  local t0 t1
  t0=$(date +%s.%N)
  "$root/build/asperity" sweep "$root/bench/sweeps/bench_threads.yaml" -j "$1" --out "$work/s$1-$2" --quiet
  t1=$(date +%s.%N)
  echo "$t0 $t1" | awk '{printf "%.3f", $2 - $1}'
}
effs=()
for ((i = 0; i < pairs; ++i)); do
  load=$(cut -d' ' -f1 /proc/loadavg)
  w1=$(wall 1 "$i")
  w2=$(wall 2 "$i")
  e=$(awk -v a="$w1" -v b="$w2" 'BEGIN {printf "%.3f", a / (2 * b)}')
  effs+=("$e")
  awk -v i="$i" -v a="$w1" -v b="$w2" -v e="$e" -v n="$points" -v l="$load" 'BEGIN {
    printf "pair %d (load %s): 1 thread %.2f s (%.2f points/s), 2 threads %.2f s (%.2f points/s), efficiency %.0f %%\n",
           i, l, a, n / a, b, n / b, 100 * e }'
done
printf '%s\n' "${effs[@]}" | sort -g | awk '{x[NR] = $1} END {
  m = NR % 2 ? x[(NR + 1) / 2] : (x[NR / 2] + x[NR / 2 + 1]) / 2
  printf "efficiency over %d pairs: median %.0f %%, range %.0f-%.0f %%\n", NR, 100 * m, 100 * x[1], 100 * x[NR] }'
