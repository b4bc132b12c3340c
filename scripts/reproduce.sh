#!/usr/bin/env bash
# Main job: set up, build, and reproduce the paper's study on the six STAND-IN experiments:
# each run through the first peak and five stick-slip cycles (event solver, default tolerance),
# in parallel; writes results/paper/ (table.csv, fig3_Q_A_t.png, fig4_A_Q.png, one run
# directory per experiment).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build/asperity reproduce scenes/paper/P*.yaml --out results/paper --set stop.cycles=5 \
  --fit fits/paper_alpha_b.yaml "$@"
