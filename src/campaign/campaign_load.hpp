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
#include "campaign/campaign_scenes.hpp"
#include "io/input_error.hpp"
#include "scene/scene.hpp"

namespace asperity {

Campaign load_campaign(const std::filesystem::path& yaml);

}  // namespace asperity
