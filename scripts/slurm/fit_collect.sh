#!/bin/bash
# The collect job after a fit's array (scripts/slurm/fit_submit.sh): writes the results folder OUT
# (fit.yaml, fitted.csv, plots) from the tasks' journals, re-running no optimization (only each
# experiment's best run, for its curves). Started by SLURM only once every task succeeded.
#SBATCH --job-name=asperity-fit-collect
#SBATCH --cpus-per-task=1
set -euo pipefail
asperity=$1 fit=$2 out=$3
exec "$asperity" fit "$fit" --collect --out "$out" --threads "${SLURM_CPUS_PER_TASK:-1}" --quiet
