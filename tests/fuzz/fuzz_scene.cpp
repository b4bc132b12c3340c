// libFuzzer: scene files (load_scene: YAML, validation, experiment resolution).
#include "fuzz_common.hpp"
#include "scene/load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = asperity::fuzz::write_input("scene.yaml", data, size);
  try {
    (void)asperity::load_scene(path);
  } catch (const asperity::io::InputError&) {
  }
  return 0;
}
