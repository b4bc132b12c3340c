#!/bin/bash
# Two sweeps started on one store: the second is refused with one clear line while the first is
# still running, and the first completes a store with exactly one row per point.
#   ASPERITY=build/asperity tests/shell/test_store_lock.sh
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
asperity=$(realpath "${ASPERITY:-$root/build/asperity}")
campaign=$root/tests/data/campaign/kill.yaml
w=$(mktemp -d -t asperity-lock.XXXXXX)
trap 'kill "$first" 2>/dev/null || true; wait 2>/dev/null || true; rm -rf "$w"' EXIT
"$asperity" sweep "$campaign" --out "$w/store" --threads 1 --quiet &
first=$!
for _ in $(seq 200); do  # until the first has journaled a point (then it holds the lock)
  [ -f "$w/store/journal.csv" ] && [ "$(wc -l < "$w/store/journal.csv")" -ge 2 ] && break
  sleep 0.05
done
set +e
"$asperity" sweep "$campaign" --out "$w/store" --threads 1 --quiet 2> "$w/second.err"
second=$?
set -e
kill -0 "$first" 2>/dev/null || { echo "FAIL: the first sweep ended before the second started (nothing proven)"; exit 1; }
if [ "$second" = 0 ] || ! grep -q "another sweep is writing" "$w/second.err" || [ "$(wc -l < "$w/second.err")" != 1 ]; then
  echo "FAIL: second sweep: exit $second, stderr:"; cat "$w/second.err"; exit 1
fi
wait "$first"
rows=$(($(wc -l < "$w/store/points.csv") - 1))
unique=$(tail -n +2 "$w/store/points.csv" | cut -d, -f1 | sort -u | wc -l)
journal=$(($(wc -l < "$w/store/journal.csv") - 1))
if [ "$rows" != 400 ] || [ "$unique" != 400 ] || [ "$journal" != 400 ]; then
  echo "FAIL: store has $rows rows ($unique indices), journal $journal lines; expected 400"; exit 1
fi
echo "OK: second sweep refused ($(cat "$w/second.err")); first completed 400 points, one row each"
