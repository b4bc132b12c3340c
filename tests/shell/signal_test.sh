#!/usr/bin/env bash
# Interrupted writes leave nothing behind (issue 21, item 5): SIGTERM (what SLURM's preemption
# sends) and SIGINT at random moments of `fit`, `run --plot`, `sweep`, `merge` and `export
# --sqlite`, and SIGXFSZ (a file-size
# limit hit while points.csv is written). After each interruption: no temporary (".NAME.tmp-*")
# beside or inside the output folders, and nothing outside them changed (the working folder's
# other files snapshotted by name, size and content hash); at the end the resumed results equal an
# uninterrupted run's.
#   tests/shell/signal_test.sh [ROUNDS]     (default 4; ctest: signal_cleanup)
# Needs build/asperity (or $ASPERITY).
set -euo pipefail
cd "$(dirname "$0")/../.."
rounds=${1:-4}
bin=$(realpath "${ASPERITY:-build/asperity}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r tests/data "$work/data"
cd "$work/data"
fail() { echo "FAIL: $*" >&2; exit 1; }

# Everything but the output folders: names, sizes and SHA-256.
outside() {
  find . -path ./f -prune -o -path ./r -prune -o -path ./s -prune -o -path ./m -prune -o -name e.db -prune -o -type f -print0 |
    sort -z | xargs -0 sha256sum
}
debris() { find . -name '.*.tmp-*' -o -name '.*.old-*' | grep -v '^$' || true; }
before=$(outside)

# Sends SIG after a random 0..MAX ms to a command started in the background; echoes its status.
interrupt() {
  local sig=$1 max=$2; shift 2
  "$bin" "$@" --quiet 2>/dev/null &
  local pid=$!
  sleep "$(printf '0.%03d' $((RANDOM % max)))"
  kill "-$sig" "$pid" 2>/dev/null || true
  local rc=0
  wait "$pid" 2>/dev/null || rc=$?
  echo "$rc"
}

fit=(fit fit/fit.yaml --out f --no-profile)
for ((i = 1; i <= rounds; i++)); do
  for sig in TERM INT; do
    rc=$(interrupt "$sig" 999 "${fit[@]}")
    [[ $rc == 0 || $rc == 143 || $rc == 130 ]] || fail "fit after SIG$sig: exit $rc"
    [[ -z $(debris) ]] || fail "fit after SIG$sig left $(debris)"
    rc=$(interrupt "$sig" 300 run fit/m010.yaml --out r --plot --set stop.time=2)
    [[ $rc == 0 || $rc == 143 || $rc == 130 ]] || fail "run after SIG$sig: exit $rc"
    [[ -z $(debris) ]] || fail "run after SIG$sig left $(debris)"
    rc=$(interrupt "$sig" 400 sweep campaign/kill.yaml --out s -j2)
    [[ $rc == 0 || $rc == 143 || $rc == 130 ]] || fail "sweep after SIG$sig: exit $rc"
    [[ -z $(debris) ]] || fail "sweep after SIG$sig left $(debris)"
  done
  echo "round $i: no debris"
done
# A file-size limit hit while points.csv is written: the write fails (EFBIG), its temporary goes.
rm -f s/points.csv
rc=0
(ulimit -f 8; "$bin" sweep campaign/kill.yaml --out s -j2 --quiet 2>"$work/xfsz.txt") || rc=$?
[[ $rc != 0 ]] || fail "sweep under a 4 KiB file-size limit succeeded"
grep -q "File too large" "$work/xfsz.txt" || fail "no 'File too large' in: $(cat "$work/xfsz.txt")"
[[ -z $(debris) ]] || fail "SIGXFSZ left $(debris)"
# Finish everything and compare with uninterrupted runs.
"$bin" "${fit[@]}" --quiet
"$bin" sweep campaign/kill.yaml --out s -j2 --quiet
"$bin" fit fit/fit.yaml --out f_ref --no-profile --quiet
"$bin" sweep campaign/kill.yaml --out s_ref -j2 --quiet
strip() { awk -F, 'BEGIN{OFS=","} {NF--; print}' "$1"; }
diff <(strip s/points.csv) <(strip s_ref/points.csv) >/dev/null || fail "the resumed store differs from a clean run"
diff <(grep -vE 'wall_s|command_line' f/fit.yaml) <(grep -vE 'wall_s|command_line' f_ref/fit.yaml) >/dev/null ||
  fail "the resumed fit differs from a clean run"
rm -rf f_ref s_ref
# merge and export --sqlite of the finished store, stopped at random moments: no temporaries, and
# a stopped merge's folder (its lock, what it wrote before its journal) is merged into again.
for ((i = 1; i <= rounds; i++)); do
  for sig in TERM INT; do
    [[ ! -f m/journal.csv ]] || rm -rf m  # done: merge never adds to a store
    rc=$(interrupt "$sig" 60 merge s --out m)
    [[ $rc == 0 || $rc == 143 || $rc == 130 ]] || fail "merge after SIG$sig: exit $rc"
    [[ -z $(debris) ]] || fail "merge after SIG$sig left $(debris)"
    rm -f e.db
    rc=$(interrupt "$sig" 60 export s --sqlite e.db)
    [[ $rc == 0 || $rc == 143 || $rc == 130 ]] || fail "export after SIG$sig: exit $rc"
    [[ -z $(debris) ]] || fail "export after SIG$sig left $(debris)"
  done
done
[[ ! -f m/journal.csv ]] || rm -rf m
"$bin" merge s --out m --quiet || fail "merge into a stopped merge's folder refused"
diff s/points.csv m/points.csv >/dev/null || fail "the merged store differs from its input"
rm -rf m e.db
[[ $(outside) == "$before" ]] || fail "files outside the output folders changed"
echo "signal test: OK ($rounds rounds of SIGTERM and SIGINT on fit, run --plot, sweep, merge and export; SIGXFSZ on a store)"
