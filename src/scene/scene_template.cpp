#include "scene/scene_template.hpp"

#include <yaml-cpp/yaml.h>

#include <mutex>
#include <optional>
#include <stdexcept>

#include "io/numbers.hpp"
#include "scene/load.hpp"

namespace asperity {

struct SceneTemplate::Impl {
  std::filesystem::path file;
  std::optional<TypedScene> typed;  // the scene with the fixed settings; nothing when invalid alone
  YAML::Node tree;
  // apply_override re-parents nodes of the tree it copies from (yaml-cpp memory merging), so
  // two variants of one tree must not be built at the same time.
  std::mutex mutex;
};

SceneTemplate SceneTemplate::load(const std::filesystem::path& scene_file,
                                  const std::vector<std::pair<std::string, std::string>>& fixed) {
  SceneTemplate t;
  t.impl_ = std::make_shared<Impl>();
  t.impl_->file = scene_file;
  YAML::Node tree = load_scene_tree(scene_file);
  for (const auto& [key, text] : fixed) tree.reset(apply_override(tree, key, YAML::Load(text)));
  t.impl_->tree.reset(tree);
  try {
    t.impl_->typed.emplace(typed_scene_from_tree(tree, scene_file));
  } catch (const io::InputError&) {
    // build() reports it (or the settings repair it) through the tree.
  }
  return t;
}

Scene SceneTemplate::build(const std::vector<SceneSetting>& settings) const {
  if (!impl_) throw std::logic_error("SceneTemplate::build on an empty template");
  if (impl_->typed) {
    std::vector<NumberSetting> typed;
    for (const auto& s : settings) {
      const SceneKey* key = find_scene_key(s.key);
      if (!TypedScene::settable(key, s.value)) break;
      typed.push_back({key, s.value});
    }
    if (typed.size() == settings.size()) return impl_->typed->with(typed);
  }
  std::lock_guard<std::mutex> lock(impl_->mutex);
  // reset(), never `tree = ...`: yaml-cpp's Node assignment writes through to the node the
  // handle refers to, which would change the template itself.
  YAML::Node tree;
  tree.reset(impl_->tree);
  for (const auto& s : settings) tree.reset(apply_override(tree, s.key, YAML::Node(io::format_double(s.value))));
  return scene_from_tree(tree, impl_->file);
}

const std::filesystem::path& SceneTemplate::file() const { return impl_->file; }

}  // namespace asperity
