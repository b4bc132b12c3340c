#!/usr/bin/env bash
# The fit journal against an uninterrupted fit (tests/data/fit/fit.yaml: alpha_b fitted separately
# to three small model-generated experiments, with a profile and an error bar; 124 evaluations):
#  (a) a fit SIGKILLed KILLS times mid-run, each rerun resuming the last, then finished: fit.yaml
#      identical to the uninterrupted one (wall times and the command line aside), the journal
#      holds each evaluation exactly once (every evaluation completed before a kill was kept and
#      not recomputed; only the ones in flight at a kill were computed again), and the last run
#      replayed + computed = the uninterrupted count;
#  (b) the fit as two array tasks (one by --task 0/2, one by --task auto with SLURM's variables)
#      plus --collect: the results folder equals the unsharded one, collect computes nothing;
#  (c) refusals, each exit 2 with exactly one line: a second fit on a folder being written, a
#      resume after an input file changed, a damaged journal line (the journal is left as it
#      was), --task on a joint fit, --collect with a task missing.
#   tests/shell/test_fit_journal.sh [KILLS]     (default 3; ctest: fit_journal_kill_resume_tasks)
# Needs build/asperity (or $ASPERITY).
set -euo pipefail
cd "$(dirname "$0")/../.."
kills=${1:-3}
bin=${ASPERITY:-build/asperity}
bin=$(realpath "$bin")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r tests/data/fit "$work/data"
cd "$work/data"
fail() { echo "FAIL: $*" >&2; exit 1; }

# Complete evaluation lines of a journal (a torn last line has no newline and is not counted).
rows() { [[ -f $1 ]] && echo $(($(wc -l < "$1") - 1)) || echo 0; }
# fit.yaml without the lines that may differ between equal fits: wall times and the command line.
same_fit() { diff <(grep -vE 'wall_s|command_line' "$1/fit.yaml") <(grep -vE 'wall_s|command_line' "$2/fit.yaml"); }
# A CSV without its wall_s column.
strip_wall() { awk -F, -v OFS=, 'NR==1{for(i=1;i<=NF;i++) if($i=="wall_s") w=i} {if(w){for(i=w;i<NF;i++) $i=$(i+1); NF--} print}' "$1"; }
same_tables() {
  for f in fitted.csv m010/evaluations.csv m015/evaluations.csv m025/evaluations.csv m010/profile.csv m025/AQ_m025_model.csv; do
    diff <(strip_wall "$1/$f") <(strip_wall "$2/$f") >/dev/null || fail "$2/$f differs from $1/$f"
  done
}
# Runs the fit expecting exit 2 and exactly one stderr line starting with $1.
refused() {
  local start=$1; shift
  local rc=0
  "$bin" fit "$@" -q 2>"$work/err" || rc=$?
  [[ $rc -eq 2 ]] || fail "exit $rc, not 2: asperity fit $*"
  [[ $(wc -l < "$work/err") -eq 1 ]] || fail "not one line: $(cat "$work/err")"
  [[ $(cat "$work/err") == "$start"* ]] || fail "expected '$start...', got: $(cat "$work/err")"
  echo "refused (exit 2): $(cat "$work/err")"
}

"$bin" fit fit.yaml --out ref --threads 2 >"$work/ref.txt"
total=$(sed -n 's/.* \([0-9]*\) computed$/\1/p' "$work/ref.txt")
[[ $total -gt 50 && $(rows ref/journal.csv) -eq $total ]] || fail "reference: $total evaluations, journal $(rows ref/journal.csv)"

# (a) Kills, each after the run journaled an evaluation of its own plus 0-30 ms.
for ((i = 1; i <= kills; i++)); do
  before=$(rows kill/journal.csv)
  "$bin" fit fit.yaml --out kill --threads 2 -q 2>/dev/null &
  pid=$!
  for ((t = 0; t < 6000; t++)); do
    (($(rows kill/journal.csv) > before)) && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.005
  done
  sleep "$(printf '0.%03d' $((RANDOM % 30)))"
  kill -9 "$pid" 2>/dev/null || true
  rc=0
  wait "$pid" 2>/dev/null || rc=$?
  after=$(rows kill/journal.csv)
  echo "kill $i: journal $before -> $after evaluations of $total, exit $rc"
  [[ $rc -eq 137 ]] || fail "run $i was not killed mid-run (exit $rc)"
  ((after > before && after < total)) || fail "kill $i did not land mid-run ($before -> $after of $total)"
done
kept=$(rows kill/journal.csv)
"$bin" fit fit.yaml --out kill --threads 2 >"$work/resume.txt"
replayed=$(sed -n 's/.*evaluations: \([0-9]*\) replayed.*/\1/p' "$work/resume.txt")
computed=$(sed -n 's/.* \([0-9]*\) computed$/\1/p' "$work/resume.txt")
echo "resume: $replayed replayed, $computed computed (journal held $kept); uninterrupted: $total"
((replayed == kept && replayed + computed == total)) || fail "replayed $replayed + computed $computed != $total"
[[ $(rows kill/journal.csv) -eq $total ]] || fail "journal holds $(rows kill/journal.csv) evaluations, not $total"
[[ $(cut -d, -f1-4 kill/journal.csv | sort -u | wc -l) -eq $((total + 1)) ]] || fail "an evaluation is journaled twice"
same_fit ref kill || fail "resumed fit.yaml differs"
same_tables ref kill

# (b) Two array tasks and the collect step.
"$bin" fit fit.yaml --out sharded --task 0/2 --threads 2 -q
SLURM_ARRAY_TASK_ID=6 SLURM_ARRAY_TASK_MIN=5 SLURM_ARRAY_TASK_MAX=6 SLURM_ARRAY_TASK_COUNT=2 \
  "$bin" fit fit.yaml --out sharded --task auto --threads 2 -q
[[ -f sharded/tasks/1-of-2/journal.csv && ! -f sharded/fit.yaml ]] || fail "tasks did not write their journals only"
"$bin" fit fit.yaml --out sharded --collect --threads 2 >"$work/collect.txt"
grep -q "evaluations: $total replayed from the journal, 0 computed" "$work/collect.txt" || fail "collect: $(cat "$work/collect.txt")"
same_fit ref sharded || fail "collected fit.yaml differs"
same_tables ref sharded
echo "tasks: 2 tasks ($(rows sharded/tasks/0-of-2/journal.csv) + $(rows sharded/tasks/1-of-2/journal.csv) evaluations) collected equal the unsharded fit"

# (c) Refusals.
"$bin" fit fit.yaml --out locked --threads 1 -q 2>/dev/null &
pid=$!
for ((t = 0; t < 6000 && $(rows locked/journal.csv) == 0; t++)); do sleep 0.005; done
refused "locked: --out: another asperity fit is writing locked" fit.yaml --out locked
kill -9 "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
echo "# edited" >> m010/measured.csv
refused "kill/inputs.txt:8: file m010/measured.csv: the file changed since the journal was computed" fit.yaml --out kill
sed -i '$d' m010/measured.csv
cp kill/journal.csv "$work/journal.bak"
sed -i '5s/,ok,/,0k,/' kill/journal.csv
cp kill/journal.csv "$work/journal.damaged"
refused "kill/journal.csv:5: check: damaged line" fit.yaml --out kill
cmp -s kill/journal.csv "$work/journal.damaged" || fail "a refused run changed the journal"
sed 's/separate: true/separate: false/' fit.yaml > joint.yaml
refused "joint.yaml: --task: a joint fit (separate: false) is one optimization" joint.yaml --task 0/2
"$bin" fit fit.yaml --out partial --task 1/2 -q
refused "partial/tasks/0-of-2: --collect: task 0/2 has not run" fit.yaml --out partial --collect
echo "fit journal test: OK ($kills kills, tasks and collect, 5 refusals)"
