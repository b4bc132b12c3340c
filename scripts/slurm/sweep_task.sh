#!/bin/bash
# One task of a campaign's SLURM job array (submitted by scripts/slurm/submit.sh): sweeps shard
# `auto` (this task of the array) into OUT.shardI. Arguments are passed by sbatch as "$1"...,
# never pasted into the script, so no path or name runs as shell code. A task that is
# preempted, killed or times out is resubmitted as is (`sbatch --array=I ...`): its store resumes.
#SBATCH --job-name=asperity-sweep
#SBATCH --cpus-per-task=1
set -euo pipefail
asperity=$1 campaign=$2 out=$3
task=$((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN))
exec "$asperity" sweep "$campaign" --shard auto --out "$out.shard$task" --threads "${SLURM_CPUS_PER_TASK:-1}" --quiet
