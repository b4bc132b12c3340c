#pragma once
// A scene file kept as a parsed tree, from which variants with some numeric values changed are
// built (fits, error-bar refits). Hides YAML from the code that builds variants.
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"

namespace asperity {

// Dotted scene keys holding one number that a fit may vary (experiment.mass, model.alpha_b, ...).
const std::vector<std::string>& numeric_scene_keys();

// The value of a numeric scene key in `scene` (std::invalid_argument for a key not listed by
// numeric_scene_keys()).
double scene_value(const Scene& scene, const std::string& key);

struct SceneSetting {  // one numeric value given to a scene key
  std::string key;
  double value = 0;
};

class SceneTemplate {
 public:
  // Parses `scene_file` and applies `fixed` (dotted key → YAML text, e.g. {"stop.at_first_peak",
  // "true"}) in order. Errors → InputError; the scene itself is validated by build().
  static SceneTemplate load(const std::filesystem::path& scene_file,
                            const std::vector<std::pair<std::string, std::string>>& fixed = {});

  // The validated scene with `settings` applied (InputError when a value is invalid for the
  // scene, e.g. model.epsilon = 1.2). Safe to call from several threads: calls on one template
  // are serialised (the tree is shared); different templates run in parallel.
  Scene build(const std::vector<SceneSetting>& settings = {}) const;

  const std::filesystem::path& file() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace asperity
