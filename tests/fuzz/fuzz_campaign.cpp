// libFuzzer: campaign files (load_campaign: YAML, grids and axes, base scenes, every axis value
// checked against the first base scene), then the scenes of the first and last points.
#include "campaign/campaign_load.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = asperity::fuzz::write_input("fuzzed_campaign.yaml", data, size);
  try {
    const asperity::Campaign c = asperity::load_campaign(path);
    (void)c.varied_keys();
    const asperity::CampaignScenes scenes(c);
    const std::uint64_t n = c.size();
    // A point's combination of values may still be refused (InputError), never crash.
    for (const std::uint64_t i : {std::uint64_t(0), n - 1}) {
      try {
        (void)scenes.scene(asperity::point_at(c, i));
      } catch (const asperity::io::InputError&) {
      }
    }
  } catch (const asperity::io::InputError&) {
  }
  return 0;
}
