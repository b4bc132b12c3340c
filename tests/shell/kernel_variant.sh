#!/usr/bin/env bash
# Runs a command with every CPU-dispatched kernel forced to one form, so that one machine runs
# the suite as a machine with another CPU would (docs/reliability.md, "Results on any CPU"):
# asperity's pinned-operator kernels (ASPERITY_KERNEL), OpenBLAS's (OPENBLAS_CORETYPE: the
# Cholesky inverse of the interacting solver) and, for the portable form, glibc's libm without its
# FMA variants (GLIBC_TUNABLES: exp, log, pow, sin, atan… round differently on CPUs with and
# without FMA).
#   tests/shell/kernel_variant.sh portable|avx2|avx512 COMMAND [ARG...]
# Exit 77 (ctest: skipped) where this CPU lacks the form.
set -euo pipefail
form=$1
shift
flags=" $(grep -m1 '^flags' /proc/cpuinfo 2>/dev/null | cut -d: -f2) "
has() {
  local f
  for f in "$@"; do [[ "$flags" == *" $f "* ]] || return 1; done
}
case "$form" in
  portable) core=Prescott ;;  # SSE3, OpenBLAS's oldest x86-64 kernels
  avx2)
    has avx2 fma bmi2 || { echo "skipped: this CPU lacks AVX2 (x86-64-v3)"; exit 77; }
    core=Haswell ;;
  avx512)
    has avx512f avx512bw avx512cd avx512dq avx512vl || { echo "skipped: this CPU lacks AVX-512 (x86-64-v4)"; exit 77; }
    core=SkylakeX ;;
  *) echo "kernel_variant.sh: unknown form '$form' (portable, avx2, avx512)" >&2; exit 2 ;;
esac
export ASPERITY_KERNEL=$form OPENBLAS_CORETYPE=$core
if [ "$form" = portable ]; then
  export GLIBC_TUNABLES="${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4"
fi
echo "ASPERITY_KERNEL=$form OPENBLAS_CORETYPE=$core${GLIBC_TUNABLES:+ GLIBC_TUNABLES=$GLIBC_TUNABLES}"
exec "$@"
