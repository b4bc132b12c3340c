#!/usr/bin/env bash
# A plausible number in the wrong unit runs (exit 0) with one warning naming the --set, the value
# and the unit slip; -q keeps it; a run without a static friction peak warns why in one line.
#   tests/shell/unit_slip_test.sh     (ctest: unit_slip_warning; needs build/asperity or $ASPERITY)
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=$(realpath "${ASPERITY:-build/asperity}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
scene=tests/data/scene/small_scene.yaml
event=(--set solver.method=event)  # the fixture's reference steps are unstable at E = 1.6 Pa (exit 3)

rc=0
"$bin" run "$scene" --out "$work/e" "${event[@]}" --set experiment.E=1.6 >"$work/out.txt" 2>"$work/err.txt" || rc=$?
[[ $rc == 0 ]] || fail "E = 1.6 Pa: exit $rc ($(cat "$work/err.txt"))"
head -n1 "$work/err.txt" | grep -Fqx "warning: --set experiment.E=1.6: experiment.E = 1.6 Pa is far below an elastomer's 1e+05 to 1e+08 Pa; was it meant in MPa (1.6e+06 Pa)?" ||
  fail "E's warning: $(cat "$work/err.txt")"
grep -q 'Q_s = nan N' "$work/out.txt" || fail "E = 1.6 Pa gave a peak: $(cat "$work/out.txt")"
tail -n1 "$work/err.txt" | grep -Eqx '.*small_scene\.yaml: Q_s = nan: no junction slipped before the run ended at t = 0\.5 s \(stop\.time 0\.5 s\); raise stop\.time, or check the scene.s values and their units' ||
  fail "no reason for Q_s = nan: $(cat "$work/err.txt")"
[[ $(wc -l <"$work/err.txt") == 2 ]] || fail "more than the warning and the reason: $(cat "$work/err.txt")"

"$bin" run "$scene" --out "$work/q" "${event[@]}" --set experiment.E=1.6 -q >"$work/out.txt" 2>"$work/err.txt" || fail "-q: exit $?"
[[ ! -s $work/out.txt ]] || fail "-q printed on stdout: $(cat "$work/out.txt")"
head -n1 "$work/err.txt" | grep -Fq "warning: --set experiment.E=1.6: experiment.E = 1.6 Pa is far below" || fail "-q dropped the warning: $(cat "$work/err.txt")"
[[ $(wc -l <"$work/err.txt") == 2 ]] || fail "-q: not the warning and the reason: $(cat "$work/err.txt")"

"$bin" run "$scene" --out "$work/m" --set experiment.mass=408 >/dev/null 2>"$work/err.txt" || fail "mass = 408 kg: exit $?"
grep -Fqx "warning: --set experiment.mass=408: experiment.mass = 408 kg is far above a slider's 0.001 to 10 kg; was it meant in g (0.408 kg)?" \
  "$work/err.txt" || fail "mass's warning: $(cat "$work/err.txt")"

"$bin" run "$scene" --out "$work/p" >/dev/null 2>"$work/err.txt" || fail "the fixture scene: exit $?"
[[ ! -s $work/err.txt ]] || fail "the fixture scene printed on stderr: $(cat "$work/err.txt")"
echo "unit slip test: OK"
