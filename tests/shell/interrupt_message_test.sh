#!/usr/bin/env bash
# Ctrl-C on `sweep` and `fit` says what was kept and how to resume (one line on stderr, exit 130),
# and the same command then resumes to the uninterrupted result.
#   tests/shell/interrupt_message_test.sh     (ctest: interrupt_message; needs build/asperity or $ASPERITY)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=$(realpath "${ASPERITY:-build/asperity}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r tests/data "$work/data"
cd "$work/data"
fail() { echo "FAIL: $*" >&2; exit 1; }

# Starts the command, waits until FILE holds at least LINES lines (work is under way), sends
# SIGINT, and leaves its exit status in $rc and its stderr in $work/err.txt.
interrupt_when() {
  local file=$1 lines=$2; shift 2
  "$bin" "$@" --quiet 2>"$work/err.txt" &
  local pid=$! i
  for ((i = 0; i < 600; i++)); do
    [[ -f $file && $(wc -l <"$file") -ge $lines ]] && break
    sleep 0.01
  done
  kill -INT "$pid"
  rc=0
  wait "$pid" || rc=$?
}

interrupt_when s/journal.csv 3 sweep campaign/kill.yaml --out s -j2
[[ $rc == 130 ]] || fail "sweep after Ctrl-C: exit $rc ($(cat "$work/err.txt"))"
grep -Eq '^kill: interrupted; [0-9]+ of 400 point\(s\) of this shard kept in s \([0-9]+ run now\); rerun the same command to resume$' \
  "$work/err.txt" || fail "sweep's message: $(cat "$work/err.txt")"
[[ $(wc -l <"$work/err.txt") == 1 ]] || fail "sweep printed more than one line: $(cat "$work/err.txt")"
"$bin" sweep campaign/kill.yaml --out s -j2 --quiet || fail "the resumed sweep failed"

interrupt_when f/journal.csv 3 fit fit/fit.yaml --out f --no-profile
[[ $rc == 130 ]] || fail "fit after Ctrl-C: exit $rc ($(cat "$work/err.txt"))"
grep -Eq '^fit: interrupted; [0-9]+ evaluation\(s\) kept in f/journal.csv; rerun the same command to resume$' \
  "$work/err.txt" || fail "fit's message: $(cat "$work/err.txt")"
[[ $(wc -l <"$work/err.txt") == 1 ]] || fail "fit printed more than one line: $(cat "$work/err.txt")"
# No evaluation the stop abandoned was journaled as a failure.
! grep -q ',nan,nan,' f/journal.csv || fail "the stop journaled a failed evaluation: $(grep ',nan,nan,' f/journal.csv)"
"$bin" fit fit/fit.yaml --out f --no-profile --quiet || fail "the resumed fit failed"
"$bin" fit fit/fit.yaml --out f_ref --no-profile --quiet
diff <(grep -vE 'wall_s|command_line' f/fit.yaml) <(grep -vE 'wall_s|command_line' f_ref/fit.yaml) >/dev/null ||
  fail "the resumed fit differs from a clean run"
echo "interrupt message test: OK"
