#!/usr/bin/env bash
# Set-up, build and the whole test suite (what CI runs): once in the Release build, once more
# under AddressSanitizer + UndefinedBehaviorSanitizer (build-san/, -O1 without debug information to keep the build short:
# it compiles in about 0.7 of -O2's time, measured on three of its heaviest files, and ASan's
# documentation asks for -O1 or higher for reasonable speed).
#   scripts/test.sh [--no-sanitizers]
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ctest --test-dir build --no-tests=error --output-on-failure -j "$(nproc)"
[ "${1:-}" = "--no-sanitizers" ] && exit 0
# The probes (bench/probes/) are built here, so that they compile; they are measurements, not tests.
cmake -S . -B build-san -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" \
  -DASPERITY_SANITIZE=ON -DASPERITY_PROBES=ON >/dev/null
ninja -C build-san -j "$(nproc)"
# halt_on_error: any report fails the test that triggered it; leaks are reported too.
ASAN_OPTIONS=halt_on_error=1:detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir build-san --no-tests=error --output-on-failure -j "$(nproc)"
