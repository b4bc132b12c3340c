#pragma once
// Campaign files (sweeps/*.yaml) → a validated Campaign (campaign/campaign.hpp), and the scene of
// each of its points. Paths are relative to the campaign file.
//
//   name: paper_exploration          # optional; the store folder (default: the file's stem)
//   description: free text           # optional
//   scenes: [../scenes/paper/P0.98N.yaml, ...]   # or `scene: one.yaml`; base scenes
//   set: {stop.time: 8, stop.cycles: 5}          # optional; applied to every point first
//   series: false                                # optional; also store each point's series.csv
//   time_limit: 600                              # optional; wall seconds per point, then failed
//   # the axes, either one grid:
//   combine: product                             # or zip (equal lengths); default product
//   axes:
//     model.eta: [0, 50, 100]                    # a list of numbers, or of texts (paths, names)
//     model.epsilon: {linspace: [0.5, 0.99, 8]}  # end points included
//     model.alpha_b: {logspace: [0.3e-15, 1.2e-15, 4]}  # geometric, end points as values
//   # or several grids, whose points are concatenated (one-at-a-time explorations):
//   grids:
//     - {name: eta_eps, axes: {model.eta: [...], model.epsilon: [...]}}
//     - {name: c_min, axes: {model.c_min: [1e-5, 1e-2]}}
//
// Any scene key may be an axis or a `set` entry: model.*, solver.*, stop.*, output.*,
// experiment (another experiment file) and experiment.<value> (mass, k_L, ...).
// Errors (InputError, "FILE:LINE: KEY: message"): unknown keys, empty axes, mixed numbers and
// texts or numbers with units in one axis, repeated values, zip axes of unequal length, an axis
// or set key the scene does not know, and any axis value the scene rejects (each value of a
// list, both end points of a space, is checked on the first base scene at load).
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "campaign/campaign.hpp"
#include "io/input_error.hpp"
#include "scene/scene.hpp"

namespace asperity {

Campaign load_campaign(const std::filesystem::path& yaml);

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

}  // namespace asperity
