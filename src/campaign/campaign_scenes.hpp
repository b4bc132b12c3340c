#pragma once
// The scene of each point of a loaded campaign (campaign_load.hpp reads the campaign).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "campaign/campaign.hpp"
#include "io/input_error.hpp"
#include "scene/scene.hpp"

namespace asperity {

// Builds the scene of each point of a loaded campaign (base scene + set + the point's axis
// values). The base scene with set and with the point's non-numeric values (another experiment
// file, a solver method) is loaded once per distinct combination; the point's numbers are set
// on its typed fields (typed_scene.hpp) and checked like the loader would. When that combination
// alone is not a valid scene, the point gets a tree of its own, parsed from the base scene's text
// (read once). Not thread-safe (both fill caches on first use): use from one thread at a time.
class CampaignScenes {
 public:
  explicit CampaignScenes(const Campaign& campaign);
  ~CampaignScenes();
  CampaignScenes(CampaignScenes&&) noexcept;

  // Throws InputError when the point's combination of values is not a valid scene.
  Scene scene(const Point& point) const;

  // The point's scene for recognising stored points cheaply, or nothing: built on the typed
  // fields of its base scene (loaded once) when every axis of the point is a plain number key
  // (model.eta, experiment.mass, ...), without reading its experiment again and without the
  // loader's checks, and without junctions and measured curve (their files are still named).
  // Never run it: a point whose hash it matches was stored from a checked scene of that very
  // text; any other point is built by scene().
  std::optional<Scene> unchecked_scene(const Point& point) const;

  // The text of a scalar scene value (`model.eta` → "100", exact) of a resolved scene; empty
  // when `key` names a map (e.g. experiment) or nothing.
  static std::string value_text(const Scene& scene, const std::string& key);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// For load_campaign: checks every base scene alone, then with each `set` entry in turn; an error
// caused by a `set` entry names its campaign line (set_lines[i]).
void check_base_scenes(const Campaign& c, const std::vector<int>& set_lines);

// A scene error caused by a campaign value, re-reported at the campaign line that set it.
[[noreturn]] void rethrow_at_campaign_line(const io::InputError& e, const std::string& campaign_file, int line,
                                           const std::string& key);

}  // namespace asperity
