#pragma once
// A validated scene, converted from its file once, from which variants with some numbers
// changed are built without YAML and without reading any file again: the scenes of sweep
// points and fit evaluations. A variant is checked like the loader checks the scene file with
// those values set (same ranges, same cross-key bounds, same messages).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "scene/scene_keys.hpp"

namespace asperity {

class TopographyCache;

struct NumberSetting {
  const SceneKey* key = nullptr;  // a key of kind number
  double value = 0;
};

class TypedScene {
 public:
  // `given_lines`: every model/solver/stop/output/experiment key the scene's tree holds, with the
  // file line of its value (0 when an override put it there). load.hpp's typed_scene_from_tree.
  // `topography`: where a variant that changes topography.* keys gets its contact (nullptr:
  // solved for each such variant).
  TypedScene(Scene scene, std::string display_file, std::map<std::string, int> given_lines,
             std::shared_ptr<TopographyCache> topography = nullptr);

  const Scene& scene() const { return scene_; }

  // Whether `with` can set this value (a number key, a finite value: a non-finite one is
  // refused by the loader's number parser, whose message only the text path gives).
  static bool settable(const SceneKey* key, double value);

  // scene() with `settings` applied in order (a later value of a key wins). InputError as
  // scene_from_tree of the scene's tree with these values set would throw. Thread-safe. A
  // topography.* value re-makes the experiment from the changed recipe (through the cache).
  Scene with(const std::vector<NumberSetting>& settings) const;

 private:
  Scene scene_;
  std::string display_;
  std::map<std::string, int> lines_;
  std::shared_ptr<TopographyCache> topography_;
};

}  // namespace asperity
