#include "solve/interacting/kernel_form.hpp"

#include <algorithm>
#include <cstdlib>
#include <string>

#include "io/input_error.hpp"

namespace asperity {

const char* kernel_form_name(KernelForm form) {
  switch (form) {
    case KernelForm::avx2:
      return "avx2";
    case KernelForm::avx512:
      return "avx512";
    default:
      return "portable";
  }
}

std::vector<KernelForm> kernel_forms_available() {
  std::vector<KernelForm> forms{KernelForm::portable};
#if defined(__x86_64__)
  if (__builtin_cpu_supports("x86-64-v3")) forms.push_back(KernelForm::avx2);
  if (__builtin_cpu_supports("x86-64-v4")) forms.push_back(KernelForm::avx512);
#endif
  return forms;
}

KernelForm kernel_form() {
  const std::vector<KernelForm> forms = kernel_forms_available();
  const char* env = std::getenv("ASPERITY_KERNEL");
  const std::string want = env ? env : "";
  if (want.empty() || want == "auto") return forms.back();
  std::string names;
  for (KernelForm f : forms) names += std::string(names.empty() ? "" : ", ") + kernel_form_name(f);
  for (KernelForm f : {KernelForm::portable, KernelForm::avx2, KernelForm::avx512}) {
    if (want != kernel_form_name(f)) continue;
    if (std::find(forms.begin(), forms.end(), f) == forms.end())
      throw io::InputError("environment", 0, "ASPERITY_KERNEL",
                           "'" + want + "': this CPU lacks that form (it runs " + names + ")");
    return f;
  }
  throw io::InputError("environment", 0, "ASPERITY_KERNEL",
                       "'" + want.substr(0, 40) + "' is not a kernel form (auto, portable, avx2 or avx512)");
}

}  // namespace asperity
