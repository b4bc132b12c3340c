// libFuzzer: junction and measured-curve CSV readers.
#include "fuzz_common.hpp"
#include "io/input_error.hpp"
#include "scene/csv.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = asperity::fuzz::write_input("fuzzed.csv", data, size);
  try {
    (void)asperity::read_junctions_csv(path);
  } catch (const asperity::io::InputError&) {
  }
  try {
    (void)asperity::read_measured_csv(path);
  } catch (const asperity::io::InputError&) {
  }
  return 0;
}
