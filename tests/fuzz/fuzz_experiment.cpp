// libFuzzer: experiment files (load_experiment, with a valid junctions.csv beside them).
#include "fuzz_common.hpp"
#include "scene/load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = asperity::fuzz::write_input("fuzzed_experiment.yaml", data, size);
  try {
    (void)asperity::load_experiment(path);
  } catch (const asperity::io::InputError&) {
  }
  return 0;
}
