#!/bin/bash
# Submits a separate fit (`separate: true`: one optimization per experiment) to SLURM: a job array
# of TASKS tasks, each `asperity fit FIT --task auto --out OUT` (its share of the experiments,
# journaled into OUT/tasks/I-of-TASKS/), and a collect job that writes the results folder OUT from
# the tasks' journals once every task succeeded (--dependency=afterok).
#   scripts/slurm/fit_submit.sh FIT.yaml OUT TASKS [sbatch options, e.g. --cpus-per-task=4 --time=1:00:00]
# Prints the two job ids ("array 123" and "collect 124"). The binary is $ASPERITY (default: the
# build/asperity next to this script's project). Tasks are submitted with --requeue: a preempted
# one goes back to the queue, a failed one is requeued by hand (`scontrol requeue ARRAY_I`) and
# resumes its journal, repeating no finished evaluation. If the collect job was cancelled because
# a task failed, submit it again: `sbatch --dependency=afterok:ARRAY scripts/slurm/fit_collect.sh
# ASPERITY FIT OUT`.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
source "$here/submit_common.sh"
check_submit_args FIT "$@"
submit_array_then "$here/fit_task.sh" collect "$here/fit_collect.sh" "$asperity" "$input" "$out"
