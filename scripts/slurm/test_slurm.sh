#!/bin/bash
# Runs a campaign and a separate fit on a real one-node SLURM cluster started here, and checks
# the merged store and the collected fit equal unsharded runs. Needs root and Debian's slurm-wlm and munge (scripts/setup.sh);
# exits 77 (ctest: skipped) without them.
#   ASPERITY=build/asperity scripts/slurm/test_slurm.sh [CAMPAIGN.yaml] [TASKS]
# It writes slurm.conf (proctrack/linuxproc, task/none, select/cons_tres with CR_CPU, this
# machine's hostname as the node) under its own temporary state folders, starts munged,
# slurmctld and slurmd, submits the array and the merge job (scripts/slurm/submit.sh), waits,
# compares, and stops exactly the daemons it started, by their pid files.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
campaign=$(realpath "${1:-$root/tests/data/campaign/tiny.yaml}")
tasks=${2:-4}
asperity=$(realpath "${ASPERITY:-$root/build/asperity}")
export ASPERITY=$asperity

# The submit scripts' argument checks need no cluster: an OUT that is a symbolic link (with or
# without a trailing slash) is refused, exit 2 and one line, before anything is submitted.
a=$(mktemp -d -t asperity-slurm-args.XXXXXX)
mkdir "$a/real"
ln -s "$a/real" "$a/out"
for script in submit.sh fit_submit.sh; do
  for out in "$a/out" "$a/out/"; do
    rc=0
    "$here/$script" "$campaign" "$out" 2 >"$a/stdout" 2>"$a/stderr" || rc=$?
    if [ $rc != 2 ] || [ "$(wc -l < "$a/stderr")" != 1 ] || ! grep -q "OUT: .*symbolic link" "$a/stderr" ||
       [ -s "$a/stdout" ] || [ -n "$(ls -A "$a/real")" ]; then
      echo "FAIL: $script with OUT a symbolic link ($out): exit $rc, stderr: $(cat "$a/stderr")"; exit 1
    fi
  done
done
rm -rf "$a"

for tool in munged slurmctld slurmd sbatch squeue sinfo; do
  if ! command -v "$tool" >/dev/null && [ ! -x "/usr/sbin/$tool" ]; then
    echo "SKIP: $tool not installed (apt-get install slurm-wlm munge)"
    exit 77
  fi
done
if [ "$(id -u)" != 0 ]; then
  echo "SKIP: the SLURM test starts slurmd and must run as root"
  exit 77
fi
PATH=$PATH:/usr/sbin

w=$(mktemp -d -t asperity-slurm.XXXXXX)
chmod 755 "$w"
mkdir -p "$w/munge" "$w/state" "$w/spool" "$w/log" "$w/out"
stop_daemons() {
  local pids=()
  for pid_file in "$w/slurmd.pid" "$w/slurmctld.pid" "$w/munge/munged.pid"; do
    [ -s "$pid_file" ] && pids+=("$(cat "$pid_file")")
  done
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for _ in $(seq 100); do  # up to 10 s for them to exit (they remove their own pid files)
    alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    [ $alive = 0 ] && break
    sleep 0.1
  done
  rm -rf "$w"
}
trap stop_daemons EXIT

# munge: its own key, socket and pid file.
dd if=/dev/urandom of="$w/munge/munge.key" bs=1024 count=1 status=none
chmod 600 "$w/munge/munge.key"
chmod 711 "$w/munge"
munged --key-file="$w/munge/munge.key" --socket="$w/munge/munge.sock" --pid-file="$w/munge/munged.pid" \
       --log-file="$w/munge/munged.log" --seed-file="$w/munge/seed" --force

host=$(hostname -s)
port=$((20000 + $$ % 20000))
cat > "$w/slurm.conf" <<CONF
ClusterName=asperitytest
SlurmctldHost=$host
AuthType=auth/munge
AuthInfo=socket=$w/munge/munge.sock
CryptoType=crypto/munge
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$w/state
SlurmdSpoolDir=$w/spool
SlurmctldPidFile=$w/slurmctld.pid
SlurmdPidFile=$w/slurmd.pid
SlurmctldLogFile=$w/log/slurmctld.log
SlurmdLogFile=$w/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=asperity Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$w/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for i in $(seq 100); do  # the node registers within seconds
  state=$(sinfo -h -o %T 2>/dev/null || true)
  [ "$state" = idle ] && break
  if [ "$i" = 100 ]; then
    echo "FAIL: the node did not come up (state '$state')"; tail -5 "$w/log/slurmctld.log" "$w/log/slurmd.log"; exit 1
  fi
  sleep 0.3
done

cd "$w/out"
ids=$("$here/submit.sh" "$campaign" "$w/out/store" "$tasks" --output="$w/out/job-%A_%a.log")
echo "$ids"
array=$(echo "$ids" | sed -n 's/^array //p')
merge=$(echo "$ids" | sed -n 's/^merge //p')
for i in $(seq 600); do  # at most 5 min
  [ -z "$(squeue -h -j "$array,$merge" 2>/dev/null)" ] && break
  if [ "$i" = 600 ]; then echo "FAIL: jobs still queued after 5 min"; squeue; exit 1; fi
  sleep 0.5
done
if [ ! -f "$w/out/store/points.csv" ]; then
  echo "FAIL: the merge job wrote no store"; tail -n 5 "$w"/out/job-*.log "$w/log/slurmctld.log"; exit 1
fi

# The same campaign unsharded, here; every value but wall_s must agree.
"$asperity" sweep "$campaign" --out "$w/out/single" --threads 1 --quiet
strip() { sed 's/,[^,]*$//' "$1"; }
if ! diff <(strip "$w/out/single/points.csv") <(strip "$w/out/store/points.csv") >/dev/null; then
  echo "FAIL: merged store differs from the unsharded run"
  diff <(strip "$w/out/single/points.csv") <(strip "$w/out/store/points.csv") | head -5
  exit 1
fi
rows=$(($(wc -l < "$w/out/store/points.csv") - 1))
shard_rows=0
for ((i = 0; i < tasks; i++)); do
  shard_rows=$((shard_rows + $(wc -l < "$w/out/store.shard$i/points.csv") - 1))
done
# A task killed mid-run, requeued (`scontrol requeue ARRAY_1`, as SLURM does on preemption with
# --requeue): its store resumes, running only the missing point (the journal ends with exactly
# one line per point, no duplicate) and giving the same values.
shard=$w/out/store.shard1
cp "$shard/points.csv" "$w/out/shard1_before.csv"
lines=$(wc -l < "$shard/journal.csv")
head -n $((lines - 1)) "$shard/journal.csv" > "$w/out/journal.cut"
cat "$w/out/journal.cut" > "$shard/journal.csv"
scontrol requeue "${array}_1"
scontrol update JobId="${array}_1" StartTime=now  # a requeued job is otherwise held ~2 min
sleep 1
for i in $(seq 600); do
  [ -z "$(squeue -h -j "$array" 2>/dev/null)" ] && break
  if [ "$i" = 600 ]; then echo "FAIL: requeued task still queued after 5 min"; exit 1; fi
  sleep 0.5
done
if [ "$(wc -l < "$shard/journal.csv")" != "$lines" ]; then
  echo "FAIL: the requeued task's journal has $(wc -l < "$shard/journal.csv") lines, expected $lines"; exit 1
fi
if ! diff <(strip "$w/out/shard1_before.csv") <(strip "$shard/points.csv") >/dev/null; then
  echo "FAIL: the requeued task's store differs from its first run"; exit 1
fi

# A separate fit (tests/data/fit/fit.yaml, three experiments) as a 2-task array plus the collect
# job (scripts/slurm/fit_submit.sh): its fit.yaml must equal an unsharded fit's (wall times and
# the command line aside), and collect must have computed no evaluation.
fit=$root/tests/data/fit/fit.yaml
ids=$("$here/fit_submit.sh" "$fit" "$w/out/fit" 2 --output="$w/out/fit-%A_%a.log")
fit_array=$(echo "$ids" | sed -n 's/^array //p')
fit_collect=$(echo "$ids" | sed -n 's/^collect //p')
for i in $(seq 600); do
  [ -z "$(squeue -h -j "$fit_array,$fit_collect" 2>/dev/null)" ] && break
  if [ "$i" = 600 ]; then echo "FAIL: fit jobs still queued after 5 min"; squeue; exit 1; fi
  sleep 0.5
done
if [ ! -f "$w/out/fit/fit.yaml" ]; then
  echo "FAIL: the collect job wrote no fit.yaml"; tail -n 5 "$w"/out/fit-*.log; exit 1
fi
"$asperity" fit "$fit" --out "$w/out/fit_single" --threads 1 --quiet
same() { grep -vE 'wall_s|command_line' "$1"; }
if ! diff <(same "$w/out/fit_single/fit.yaml") <(same "$w/out/fit/fit.yaml") >/dev/null; then
  echo "FAIL: the collected fit differs from the unsharded fit"
  diff <(same "$w/out/fit_single/fit.yaml") <(same "$w/out/fit/fit.yaml") | head -5
  exit 1
fi
fit_evals=$(($(wc -l < "$w/out/fit/tasks/0-of-2/journal.csv") + $(wc -l < "$w/out/fit/tasks/1-of-2/journal.csv") - 2))

echo "OK: $tasks array tasks (job $array) + merge (job $merge) on SLURM $(sinfo -V | cut -d' ' -f2): $rows points, $shard_rows in the shards, identical to the unsharded run; a requeued task resumed its store;" \
     "a fit as 2 array tasks (job $fit_array, $fit_evals evaluations journaled) + collect (job $fit_collect) equals the unsharded fit"
