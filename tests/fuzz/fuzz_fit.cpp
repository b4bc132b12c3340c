// libFuzzer: fit files (load_fit: YAML, parameters, experiments through their scenes, optimizer,
// profile, error bars; the work dir holds a valid scene.yaml with a measured curve to refer to).
#include "fit/fit_load.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = asperity::fuzz::write_input("fuzzed_fit.yaml", data, size);
  try {
    (void)asperity::load_fit(path);
  } catch (const asperity::io::InputError&) {
  }
  return 0;
}
