#!/bin/bash
# Submits a campaign to SLURM: a job array of TASKS shards, each `asperity sweep --shard auto`
# into OUT.shardI, and a merge job into OUT that starts once every task succeeded.
#   scripts/slurm/submit.sh CAMPAIGN.yaml OUT TASKS [sbatch options, e.g. --cpus-per-task=8 --time=2:00:00]
# Prints the two job ids ("array 123" and "merge 124"). The binary is $ASPERITY (default: the
# build/asperity next to this script's project). Array tasks are submitted with --requeue, so a
# preempted one goes back to the queue; a failed one is requeued by hand with
# `scontrol requeue ARRAY_I` (same task, same shard: its store resumes). If the merge job was
# cancelled because a task failed, submit it again: `sbatch --dependency=afterok:ARRAY
# scripts/slurm/merge_task.sh ASPERITY OUT TASKS`. (A new `sbatch --array=I` would be a
# one-task array, shard 0/1: not the same shard.)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
if [ $# -lt 3 ]; then
  echo "usage: $0 CAMPAIGN.yaml OUT TASKS [sbatch options...]" >&2
  exit 2
fi
campaign=$1 out=$2 tasks=$3
shift 3
if ! [[ $tasks =~ ^[1-9][0-9]{0,4}$ ]]; then
  echo "$0: TASKS: expected a whole number in [1, 99999], got '$tasks'" >&2
  exit 2
fi
if [ ! -f "$campaign" ]; then
  echo "$0: CAMPAIGN: no such file: $campaign" >&2
  exit 2
fi
asperity=${ASPERITY:-$here/../../build/asperity}
asperity=$(realpath "$asperity")
campaign=$(realpath "$campaign")
out=$(realpath -m "$out")
array=$(sbatch --parsable --requeue --array="0-$((tasks - 1))" "$@" "$here/sweep_task.sh" "$asperity" "$campaign" "$out")
array=${array%%;*}
merge=$(sbatch --parsable --dependency="afterok:$array" "$@" "$here/merge_task.sh" "$asperity" "$out" "$tasks")
merge=${merge%%;*}
echo "array $array"
echo "merge $merge"
