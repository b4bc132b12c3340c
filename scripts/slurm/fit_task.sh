#!/bin/bash
# One task of a fit's SLURM job array (submitted by scripts/slurm/fit_submit.sh): runs this task's
# share of the fit's per-experiment optimizations (`--task auto`), journaled into
# OUT/tasks/I-of-N/. Arguments come from sbatch as "$1"..., never pasted into shell code. A task
# preempted, killed or timed out and requeued resumes its journal.
#SBATCH --job-name=asperity-fit
#SBATCH --cpus-per-task=1
set -euo pipefail
asperity=$1 fit=$2 out=$3
exec "$asperity" fit "$fit" --task auto --out "$out" --threads "${SLURM_CPUS_PER_TASK:-1}" --quiet
