#!/usr/bin/env bash
# Kill test of the sweep store: runs a campaign uninterrupted, then again into a second store
# killed with SIGKILL at random instants KILLS times (each rerun resumes the last), finishes it,
# and compares the two stores: every point present once, values identical (wall_s aside).
#   scripts/kill_test.sh [CAMPAIGN] [KILLS]     (default tests/data/campaign/kill.yaml, 20)
# Needs build/asperity (or $ASPERITY). Exit 0 when the stores agree.
set -euo pipefail
cd "$(dirname "$0")/.."
campaign=${1:-tests/data/campaign/kill.yaml}
kills=${2:-20}
bin=${ASPERITY:-build/asperity}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$bin" sweep "$campaign" --out "$work/ref" --quiet -j2
total=$(($(wc -l < "$work/ref/points.csv") - 1))

killed=0
for ((i = 1; i <= kills; i++)); do
  "$bin" sweep "$campaign" --out "$work/kill" --quiet -j2 2>/dev/null &
  pid=$!
  sleep "$(printf '0.%03d' $((RANDOM % 600)))"
  if kill -9 "$pid" 2>/dev/null; then killed=$((killed + 1)); fi
  wait "$pid" 2>/dev/null || true
done
"$bin" sweep "$campaign" --out "$work/kill" --quiet -j2

strip() { awk -F, 'BEGIN{OFS=","} {NF--; print}' "$1"; }  # drop wall_s (last column)
rows=$(($(wc -l < "$work/kill/points.csv") - 1))
unique=$(tail -n +2 "$work/kill/points.csv" | cut -d, -f1 | sort -u | wc -l)
journal=$(($(wc -l < "$work/kill/journal.csv") - 1))
echo "kill test: $killed SIGKILLs landed of $kills; $rows rows ($unique distinct points, $total expected);" \
     "journal $journal lines"
if [[ $rows -ne $total || $unique -ne $total ]]; then
  echo "FAIL: lost or duplicated points" >&2
  exit 1
fi
if ! diff <(strip "$work/ref/points.csv") <(strip "$work/kill/points.csv") >"$work/diff.txt"; then
  echo "FAIL: values differ from the uninterrupted run:" >&2
  head -20 "$work/diff.txt" >&2
  exit 1
fi
echo "kill test: OK (stores identical apart from wall_s)"
