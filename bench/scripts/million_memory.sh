#!/bin/bash
# Peak resident memory of `asperity run` on a synthetic 10^6-junction experiment (README figure).
# Population: power law tau = 1.5 on [1e-12, 1e-10] m^2 (mean 1e-11, so sum A0 = 10 mm^2), drawn
# deterministically as the quantiles (i + 1/2)/N of the distribution (no random numbers); P4.00N
# apparatus. The 23 MB junction file is written to a temporary folder, not shipped.
# Usage: bench/scripts/million_memory.sh [STOP_TIME_S (default 0.2)] [N (default 1000000)]
set -euo pipefail
stop=${1:-0.2}
n=${2:-1000000}
root=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/asperity-million.XXXXXX")
trap 'rm -rf "$work"' EXIT
awk -v n="$n" 'BEGIN {
  lo = 1e-12; hi = 1e-10; a = lo ^ -0.5; b = hi ^ -0.5
  print "area_m2"
  for (i = 0; i < n; ++i) { u = (i + 0.5) / n; printf "%.17g\n", (a - u * (a - b)) ^ -2 }
}' > "$work/junctions.csv"
cat > "$work/experiment.yaml" <<YAML
name: "million"
description: "synthetic: 10^6 junctions, power law tau = 1.5 on [1e-12, 1e-10] m^2 (quantile grid), P4.00N apparatus"
mass: 0.408
k_L: 9200
v: 1e-04
E: 1600000
nu: 0.5
sigma_exp: 230000
junctions: "junctions.csv"
YAML
printf 'experiment: experiment.yaml\nstop:\n  time: %s\n' "$stop" > "$work/scene.yaml"
/usr/bin/time -v "$root/build/asperity" run "$work/scene.yaml" --out "$work/run" 2> "$work/time.txt"
grep -E "^ *(N|steps|slips|t_end|wall_s):" "$work/run/summary.yaml"
grep -E "Maximum resident|Elapsed|User time" "$work/time.txt"
