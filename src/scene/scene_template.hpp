#pragma once
// A scene file loaded once, from which variants with some numeric values changed are built
// (fits, error-bar refits): typed fields set on the loaded scene (typed_scene.hpp), no text and
// no file read per variant. Hides YAML from the code that builds variants.
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene.hpp"
#include "scene/scene_keys.hpp"  // numeric_scene_keys, scene_value

namespace asperity {

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
  // scene, e.g. model.epsilon = 1.2). Safe to call from several threads. When the scene with
  // only the fixed settings is itself invalid (a setting may repair it) or a value is not
  // finite, the variant is built from the parsed tree instead (calls then serialised).
  Scene build(const std::vector<SceneSetting>& settings = {}) const;

  const std::filesystem::path& file() const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;
};

}  // namespace asperity
