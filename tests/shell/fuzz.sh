#!/usr/bin/env bash
# Fuzzes the input loaders with libFuzzer (+ ASan/UBSan) for a bounded time.
#   tests/shell/fuzz.sh [SECONDS_PER_TARGET=60] [TARGET...]
# Seeds come from the shipped files (scenes, experiments, CSVs, sweeps, fits, the bad-input
# corpus); the growing corpus and any crash-* files stay in build-fuzz/. A crash is a bug: turn
# the input into a case under tests/bad_inputs/ (or a unit test) and fix the loader.
set -euo pipefail
cd "$(dirname "$0")/../.."
secs=${1:-60}; shift || true
if ! command -v clang++ >/dev/null; then apt-get update -qq && apt-get install -y -qq clang; fi
scripts/setup.sh --deps-only
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DASPERITY_FUZZ=ON -DASPERITY_TESTS=OFF >/dev/null
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=($(ls tests/fuzz/fuzz_*.cpp | xargs -n1 basename | sed 's/\.cpp$//'))
cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]}"
for t in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$t; mkdir -p "$corpus" build-fuzz/crashes/$t
  case $t in
    fuzz_scene) seeds=(scenes/paper/*.yaml tests/bad_inputs/scene_*.yaml) ;;
    fuzz_experiment) seeds=(data/standin/*/experiment.yaml tests/bad_inputs/experiment_*.yaml) ;;
    fuzz_csv) seeds=(tests/bad_inputs/*.csv data/standin/P0.98N/measured.csv) ;;
    fuzz_campaign) seeds=(sweeps/*.yaml tests/bad_inputs/campaign_*.yaml) ;;
    fuzz_fit) seeds=(fits/*.yaml tests/bad_inputs/fit_*.yaml) ;;
    *) seeds=() ;;
  esac
  for f in "${seeds[@]}"; do [ -f "$f" ] && cp "$f" "$corpus/seed-$(basename "$f")"; done
  echo "== $t: ${secs}s"
  (cd build-fuzz/crashes/$t && ../../$t -max_total_time="$secs" -max_len=4096 -timeout=10 \
     -print_final_stats=1 ../../corpus/$t 2>&1 | grep -E "^#|stat::|ERROR|SUMMARY|Done" | tail -8)
  n=$(ls build-fuzz/crashes/$t | wc -l)
  echo "$t: $n crash/timeout files in build-fuzz/crashes/$t"
  [ "$n" -eq 0 ] || exit 1
done
