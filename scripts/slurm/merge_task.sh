#!/bin/bash
# The merge job after a campaign's array (scripts/slurm/submit.sh): merges OUT.shard0 ...
# OUT.shard(N-1) into OUT. Started by SLURM only once every array task succeeded
# (--dependency=afterok), so it never merges a shard that is still running.
#SBATCH --job-name=asperity-merge
#SBATCH --cpus-per-task=1
set -euo pipefail
asperity=$1 out=$2 tasks=$3
shards=()
for ((i = 0; i < tasks; i++)); do shards+=("$out.shard$i"); done
exec "$asperity" merge "${shards[@]}" --out "$out" --quiet
