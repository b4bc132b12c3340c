#pragma once
// The synthetic-experiment recipe (a YAML file with a top-level `synthetic:` section): a base
// scene, the model's settings to generate with (the truth), noise levels and the sampling of the
// measured curves. `asperity generate` runs the scene once and writes an experiment folder that
// `asperity fit` reads like a stand-in (generate/synthetic.hpp, docs/calibration.md, "Synthetic
// experiments and model recovery"). Strict reader: unknown keys, wrong types and bad values are
// InputError "FILE:LINE: KEY: message".
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"

namespace asperity {

struct SyntheticRecipe {
  std::filesystem::path file;        // the recipe (provenance)
  std::filesystem::path scene_file;  // the base scene, as resolved
  std::string scene_rel;             // ... as written in the recipe
  // The truth: `set:` entries (dotted model.* / solver.* keys, values as YAML text) in file order,
  // and the base scene with them applied (checked by the scene loader).
  std::vector<std::pair<std::string, std::string>> set;
  Scene scene;
  std::string name;            // experiment name (default: the base experiment's + "-synthetic")
  std::uint64_t seed = 0;      // area noise: splitmix64(seed ^ "noise"); force noise: ^ "force"
  double noise_area = 0.002;   // std of the noise on A, in units of Σ A0
  double noise_force = 0.002;  // std of the noise on Q, in units of the run's largest Q in the window
  int points = 40;             // A(Q): Q equally spaced on [0, Q_s] (Q_s: the run's first peak)
  double force_every = 0.005;  // s, Q(t) sampling (also the run's output.every)
  double force_end = 0.0;      // s, Q(t) window [0, force_end]: the run's stop.time
};

// Whether the YAML file at `path` has a top-level `synthetic:` key (parse errors: InputError).
bool is_synthetic_recipe(const std::filesystem::path& path);

// Reads and validates a recipe, loading its base scene with `set` applied. Throws InputError.
SyntheticRecipe load_synthetic_recipe(const std::filesystem::path& path);

}  // namespace asperity
