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
if [ $# -lt 3 ]; then
  echo "usage: $0 FIT.yaml OUT TASKS [sbatch options...]" >&2
  exit 2
fi
fit=$1 out=$2 tasks=$3
shift 3
if ! [[ $tasks =~ ^[1-9][0-9]{0,4}$ ]]; then
  echo "$0: TASKS: expected a whole number in [1, 99999], got '$tasks'" >&2
  exit 2
fi
if [ ! -f "$fit" ]; then
  echo "$0: FIT: no such file: $fit" >&2
  exit 2
fi
asperity=${ASPERITY:-$here/../../build/asperity}
asperity=$(realpath "$asperity")
fit=$(realpath "$fit")
out=$(realpath -m "$out")
array=$(sbatch --parsable --requeue --array="0-$((tasks - 1))" "$@" "$here/fit_task.sh" "$asperity" "$fit" "$out")
array=${array%%;*}
collect=$(sbatch --parsable --dependency="afterok:$array" "$@" "$here/fit_collect.sh" "$asperity" "$fit" "$out")
collect=${collect%%;*}
echo "array $array"
echo "collect $collect"
