#include "generate/synthetic_recipe.hpp"

#include <yaml-cpp/yaml.h>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/load.hpp"

namespace asperity {

namespace fs = std::filesystem;

namespace {

using io::MapView;
using io::Source;

double positive(const MapView& m, const YAML::Node& n, const std::string& k, const char* unit) {
  const double x = m.number(n, k, unit);
  if (!(x > 0.0)) m.fail_at(n, k, "must be > 0, got " + io::format_double(x));
  return x;
}

// A relative noise level: 0 (exact data) up to 10 % (beyond, the noise is the signal).
double noise_level(const MapView& m, const std::string& k, double fallback) {
  const auto n = m.find(k);
  if (!n) return fallback;
  const double x = m.number(*n, k, nullptr);
  if (!(x >= 0.0 && x < 0.1)) m.fail_at(*n, k, "must be in [0, 0.1), got " + io::format_double(x));
  return x;
}

// The generator owns the experiment, the stop and the output of the run: `set` may change only
// how the model behaves and how it is solved.
bool settable(const std::string& key) { return key.rfind("model.", 0) == 0 || key.rfind("solver.", 0) == 0; }

// The base scene with `set` applied. A bad value is reported at its line in the recipe.
Scene truth_scene(const MapView& top, SyntheticRecipe& r, const YAML::Node& scene_node, const YAML::Node* set_node) {
  YAML::Node tree = io::load_yaml_file(r.scene_file, io::input_path(r.scene_file));
  std::vector<std::pair<std::string, YAML::Node>> entries;
  if (set_node) {
    if (!set_node->IsMap() || set_node->size() == 0)
      top.fail_at(
          *set_node, "set",
          "expected a map of dotted scene keys, e.g. {model.alpha_b: 0.7e-15}, got " + io::node_kind(*set_node));
    for (auto it = set_node->begin(); it != set_node->end(); ++it) {
      const std::string key = it->first.Scalar();
      if (!settable(key))
        top.fail_at(it->first, "set." + key,
                    "only model.* and solver.* keys may be set (the generator sets the experiment, stop and output)");
      entries.emplace_back(key, it->second);
      r.set.emplace_back(key, YAML::Dump(it->second));
    }
  }
  for (const auto& [key, value] : entries) {
    try {
      tree = apply_override(tree, key, value);
    } catch (const io::InputError& e) {
      top.fail_at(value, "set." + key, e.message);
    }
  }
  try {
    return scene_from_tree(tree, r.scene_file);
  } catch (const io::InputError& e) {
    for (const auto& [key, value] : entries)  // the error is one of ours when it names our key
      if (e.key == key || e.key.rfind(key + ".", 0) == 0) top.fail_at(value, "set." + key, e.message);
    top.fail_at(scene_node, "scene", std::string("the base scene is not valid: ") + e.what());
  }
}

}  // namespace

bool is_synthetic_recipe(const fs::path& path) {
  const YAML::Node root = io::load_yaml_file(path, io::input_path(path));
  if (!root.IsMap()) return false;
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == "synthetic") return true;
  return false;
}

SyntheticRecipe load_synthetic_recipe(const fs::path& path) {
  const std::string display = io::input_path(path);
  const YAML::Node root = io::load_yaml_file(path, display);
  const Source src{display, nullptr};
  const MapView outer(src, root, "", {"synthetic"});
  const MapView top(src, outer.require("synthetic"), "synthetic",
                    {"scene", "set", "name", "seed", "noise", "measured", "measured_force"});
  SyntheticRecipe r;
  r.file = path;

  const YAML::Node sn = top.require("scene");
  r.scene_rel = top.string(sn, "scene");
  r.scene_file = path.parent_path() / fs::path(r.scene_rel);
  {
    std::error_code ec;
    if (!fs::is_regular_file(r.scene_file, ec))
      top.fail_at(
          sn, "scene",
          "scene file not found: " + io::quote(r.scene_rel) + " (looked for " + io::input_path(r.scene_file) + ")");
  }
  const auto set_node = top.find("set");
  r.scene = truth_scene(top, r, sn, set_node ? &*set_node : nullptr);
  if (r.scene.experiment.junctions.size() == 0)
    top.fail_at(sn, "scene", "the base scene's experiment has no junctions");

  r.name = r.scene.experiment.name + "-synthetic";
  if (auto n = top.find("name")) {
    r.name = top.string(*n, "name");
    if (r.name.empty()) top.fail_at(*n, "name", "must not be empty");
  }
  r.seed = top.seed(top.require("seed"), "seed");

  if (auto nn = top.find("noise")) {
    const MapView m(src, *nn, "synthetic.noise", {"area", "force"});
    r.noise_area = noise_level(m, "area", r.noise_area);
    r.noise_force = noise_level(m, "force", r.noise_force);
  }
  if (auto mn = top.find("measured")) {
    const MapView m(src, *mn, "synthetic.measured", {"points"});
    if (auto n = m.find("points")) {
      r.points = m.integer(*n, "points");
      if (r.points < 2) m.fail_at(*n, "points", "must be at least 2");
    }
  }
  {
    const MapView m(src, top.require("measured_force"), "synthetic.measured_force", {"every", "end"});
    if (auto n = m.find("every")) r.force_every = positive(m, *n, "every", "s");
    const YAML::Node en = m.require("end");
    r.force_end = positive(m, en, "end", "s");
    if (!(r.force_end >= 2 * r.force_every)) m.fail_at(en, "end", "must be at least two samples (2 * every) long");
  }
  return r;
}

}  // namespace asperity
