#include "scene/scene_template.hpp"

#include <yaml-cpp/yaml.h>

#include <mutex>
#include <stdexcept>

#include "scene/load.hpp"
#include "io/numbers.hpp"

namespace asperity {

struct SceneTemplate::Impl {
  std::filesystem::path file;
  YAML::Node tree;
  // apply_override re-parents nodes of the tree it copies from (yaml-cpp memory merging), so
  // two variants of one tree must not be built at the same time.
  std::mutex mutex;
};

namespace {

struct NumericKey {
  const char* key;
  double (*get)(const Scene&);
};

const NumericKey kNumericKeys[] = {
    {"experiment.mass", [](const Scene& s) { return s.experiment.mass_kg; }},
    {"experiment.k_L", [](const Scene& s) { return s.experiment.k_L; }},
    {"experiment.v", [](const Scene& s) { return s.experiment.v; }},
    {"experiment.E", [](const Scene& s) { return s.experiment.E; }},
    {"experiment.nu", [](const Scene& s) { return s.experiment.nu; }},
    {"experiment.sigma_exp", [](const Scene& s) { return s.experiment.sigma_exp; }},
    {"model.eta", [](const Scene& s) { return s.model.eta; }},
    {"model.epsilon", [](const Scene& s) { return s.model.epsilon; }},
    {"model.c_min", [](const Scene& s) { return s.model.c_min; }},
    {"model.p", [](const Scene& s) { return s.model.p; }},
    {"model.alpha_b", [](const Scene& s) { return s.model.alpha_b; }},
};

}  // namespace

const std::vector<std::string>& numeric_scene_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const auto& n : kNumericKeys) k.emplace_back(n.key);
    return k;
  }();
  return keys;
}

double scene_value(const Scene& scene, const std::string& key) {
  for (const auto& n : kNumericKeys)
    if (key == n.key) return n.get(scene);
  throw std::invalid_argument("not a numeric scene key: " + key);
}

SceneTemplate SceneTemplate::load(const std::filesystem::path& scene_file,
                                  const std::vector<std::pair<std::string, std::string>>& fixed) {
  SceneTemplate t;
  t.impl_ = std::make_shared<Impl>();
  t.impl_->file = scene_file;
  YAML::Node tree = load_scene_tree(scene_file);
  for (const auto& [key, text] : fixed) tree.reset(apply_override(tree, key, YAML::Load(text)));
  t.impl_->tree.reset(tree);
  return t;
}

Scene SceneTemplate::build(const std::vector<SceneSetting>& settings) const {
  if (!impl_) throw std::logic_error("SceneTemplate::build on an empty template");
  std::lock_guard<std::mutex> lock(impl_->mutex);
  // reset(), never `tree = ...`: yaml-cpp's Node assignment writes through to the node the
  // handle refers to, which would change the template itself.
  YAML::Node tree;
  tree.reset(impl_->tree);
  for (const auto& s : settings)
    tree.reset(apply_override(tree, s.key, YAML::Node(scene_io::format_double(s.value))));
  return scene_from_tree(tree, impl_->file);
}

const std::filesystem::path& SceneTemplate::file() const { return impl_->file; }

}  // namespace asperity
