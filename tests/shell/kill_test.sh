#!/usr/bin/env bash
# Kill test of the sweep store: runs a campaign uninterrupted, then again into a second store
# killed with SIGKILL KILLS times (each rerun resumes the last), finishes it, and compares the two
# stores: every point present once, values identical (wall_s aside).
#   tests/shell/kill_test.sh [CAMPAIGN] [KILLS]     (default tests/data/campaign/kill.yaml, 20)
# ctest runs a short form (4 kills, a few seconds): kill_test_short in CMakeLists.txt.
# Needs build/asperity (or $ASPERITY). Exit 0 when the stores agree.
#
# Each kill is shown to land mid-run, or the test fails: the kill is sent only once the run has
# appended a row of its own to the journal (so it is past start-up and inside its point loop),
# after a further random 0-50 ms; the run must then die of the SIGKILL (exit 137, not finished),
# and the journal must hold more rows than before that run and fewer than the campaign's points.
# A run inside its point loop with points left always has points in flight (the pipeline keeps
# up to 2 per thread started), so each kill interrupted at least one point; the rows it had
# written survived it and the next run did not redo them.
set -euo pipefail
cd "$(dirname "$0")/../.."
campaign=${1:-tests/data/campaign/kill.yaml}
kills=${2:-20}
bin=${ASPERITY:-build/asperity}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$bin" sweep "$campaign" --out "$work/ref" --quiet -j2
total=$(($(wc -l < "$work/ref/points.csv") - 1))

# Complete rows of the journal (a torn last line has no newline and is not counted).
rows() {
  local j="$work/kill/journal.csv"
  [[ -f $j ]] || { echo 0; return; }
  local n=$(($(wc -l < "$j") - 1))
  echo $((n < 0 ? 0 : n))
}

torn=0
for ((i = 1; i <= kills; i++)); do
  before=$(rows)
  "$bin" sweep "$campaign" --out "$work/kill" --quiet -j2 2>/dev/null &
  pid=$!
  # Wait (at most 60 s) for this run's first row of its own, then a random part of a point more.
  for ((t = 0; t < 12000; t++)); do
    (($(rows) > before)) && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.005
  done
  sleep "$(printf '0.%03d' $((RANDOM % 50)))"
  kill -9 "$pid" 2>/dev/null || true
  rc=0
  wait "$pid" 2>/dev/null || rc=$?
  after=$(rows)
  [[ -s $work/kill/journal.csv && $(tail -c 1 "$work/kill/journal.csv" | od -An -c | tr -d ' ') != '\n' ]] && torn=$((torn + 1))
  echo "kill $i: journal $before -> $after rows of $total, exit $rc"
  if [[ $rc -ne 137 ]]; then
    echo "FAIL: run $i was not killed mid-run (exit $rc, 137 = SIGKILL)" >&2
    exit 1
  fi
  if ((after <= before || after >= total)); then
    echo "FAIL: kill $i did not land inside the point loop (journal $before -> $after rows of $total)" >&2
    exit 1
  fi
done
"$bin" sweep "$campaign" --out "$work/kill" --quiet -j2

strip() { awk -F, 'BEGIN{OFS=","} {NF--; print}' "$1"; }  # drop wall_s (last column)
rows_final=$(($(wc -l < "$work/kill/points.csv") - 1))
unique=$(tail -n +2 "$work/kill/points.csv" | cut -d, -f1 | sort -u | wc -l)
journal=$(($(wc -l < "$work/kill/journal.csv") - 1))
echo "kill test: $kills SIGKILLs, each mid-run ($torn tore the journal's last line);" \
     "$rows_final rows ($unique distinct points, $total expected); journal $journal lines"
if [[ $rows_final -ne $total || $unique -ne $total || $journal -ne $total ]]; then
  echo "FAIL: lost, duplicated or recomputed points" >&2
  exit 1
fi
if ! diff <(strip "$work/ref/points.csv") <(strip "$work/kill/points.csv") >"$work/diff.txt"; then
  echo "FAIL: values differ from the uninterrupted run:" >&2
  head -20 "$work/diff.txt" >&2
  exit 1
fi
echo "kill test: OK (stores identical apart from wall_s)"
