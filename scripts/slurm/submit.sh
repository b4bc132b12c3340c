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
source "$here/submit_common.sh"
check_submit_args CAMPAIGN "$@"
submit_array_then "$here/sweep_task.sh" merge "$here/merge_task.sh" "$asperity" "$out" "$tasks"
