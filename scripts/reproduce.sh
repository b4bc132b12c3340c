#!/usr/bin/env bash
# Main job: set up, build, and run the paper's six experiments on the STAND-IN data.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
mkdir -p results/paper
summary=results/paper/table.csv
echo "experiment,N,A0_m2,dt_s,Q_s_N,A_s_m2,t_peak_s,alpha_m2_per_N2,alpha_R2,shape_exponent,ss_drop_N,ss_period_s" > "$summary.tmp"
for scene in scenes/paper/P*.yaml; do
  name=$(basename "$scene" .yaml)
  build/asperity run "$scene" --out "results/paper/$name" --set stop.time=8 --set stop.cycles=5
  s="results/paper/$name/summary.yaml"
  get() { awk -v k="$1" -F': ' '$1==k {print $2}' "$s"; }
  echo "$name,$(get N),$(get A0),$(get dt),$(get Q_s),$(get A_s),$(get t_peak),$(get alpha),$(get alpha_R2),$(get shape_exponent),$(get ss_drop),$(get ss_period)" >> "$summary.tmp"
done
mv "$summary.tmp" "$summary"
echo "STAND-IN data: these numbers are not properties of the real experiments."
column -s, -t "$summary"
