#pragma once
// Which form of the pinned operator's SIMD kernels a run uses (pinned_kernels.cpp): the
// widest this CPU runs, or the one the environment variable ASPERITY_KERNEL names, so that one
// machine can run every form its CPU has (the test suite does: tests/shell/kernel_variant.sh).
// The forms group every sum of the chord passes alike (the same bits); only the row norms of
// G's single-precision copy are summed in another order (within their rounding allowance), which
// can move a pass between the copy and G only at a tie (docs/reliability.md, "Results on any CPU").
#include <vector>

namespace asperity {

enum class KernelForm { portable, avx2, avx512 };

const char* kernel_form_name(KernelForm form);
// The forms this CPU runs, narrowest first (portable always; AVX2 = x86-64-v3, AVX-512 =
// x86-64-v4).
std::vector<KernelForm> kernel_forms_available();
// ASPERITY_KERNEL unset, empty or "auto": the widest available form; "portable", "avx2" or
// "avx512": that form. Another value, or a form this CPU lacks, throws InputError naming the
// variable (exit 2).
KernelForm kernel_form();

}  // namespace asperity
