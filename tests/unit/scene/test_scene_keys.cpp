// src/scene/scene_keys, typed_scene: the key table against the struct defaults and the writer,
// and variants built on typed fields against the same values set in the YAML tree (the loader).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "io/numbers.hpp"
#include "scene/load.hpp"
#include "scene/scene_keys.hpp"
#include "scene/typed_scene.hpp"

namespace fs = std::filesystem;
using namespace asperity;

namespace {

const fs::path kScene = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "scene" / "small_scene.yaml";

// The scene text, or "error: <what()>".
template <class F>
std::string outcome(F&& build) {
  try {
    return scene_to_yaml(build());
  } catch (const io::InputError& e) {
    return std::string("error: ") + e.what();
  }
}

}  // namespace

TEST_CASE("scene keys: number defaults are the struct defaults and the writer prints every key", "[scene]") {
  const Scene defaults;
  int numbers = 0;
  for (const SceneKey& k : scene_keys()) {
    INFO(k.name);
    CHECK(find_scene_key(k.name) == &k);
    if (k.kind == KeyKind::number && !std::isnan(k.default_value)) {
      CHECK(k.get(defaults) == k.default_value);
      ++numbers;
    }
  }
  // model 7 (eta, epsilon, c_min, p, alpha_b, interaction_cutoff, position_scale), solver 3
  // (Ct, tolerance, interaction_tolerance), stop 3, output 2; experiment values are required.
  CHECK(numbers == 15);
  const Scene s = load_scene(kScene, {"stop.max_slips=7", "stop.wall_time=60"});
  const std::string text = scene_to_yaml(s);
  for (const SceneKey& k : scene_keys()) {
    INFO(k.name);
    const std::string v = k.text(s);
    if (k.written && !k.written(s) &&
        k.section() == "topography") {  // no section at all (its E, nu are experiment's leaves too)
      CHECK(text.find("\ntopography:") == std::string::npos);
      continue;
    }
    if (k.written && !k.written(s)) {  // e.g. the interaction keys of a scene without interactions
      CHECK(text.find("  " + k.leaf() + ": ") == std::string::npos);
      continue;
    }
    CHECK(text.find("  " + k.leaf() + ": " + (k.kind == KeyKind::text ? io::yaml_quoted(v) : v) + "\n") !=
          std::string::npos);
  }
  CHECK(scene_value_text(s, "model.eta") == "50");
  CHECK(scene_value_text(s, "stop.max_slips") == "7");
  CHECK(scene_value_text(load_scene(kScene), "stop.max_slips").empty());  // not written at its default
  CHECK(scene_value_text(s, "output.series").empty());
  CHECK(numeric_scene_keys().size() == 12);
  CHECK_THROWS_AS(scene_value(s, "solver.Ct"), std::invalid_argument);  // not a fit parameter
}

TEST_CASE("scene keys: a typed variant equals the tree with the same values, errors included", "[scene]") {
  const YAML::Node tree = load_scene_tree(kScene);
  const TypedScene typed = typed_scene_from_tree(tree, kScene);
  struct Case {
    std::vector<std::pair<std::string, double>> set;
  };
  const std::vector<Case> cases{
      {{{"model.eta", 75}}},
      {{{"experiment.mass", 0.1 + 0.2}}},
      {{{"stop.time", 0.25}, {"model.p", 2}, {"solver.Ct", 500}}},
      {{{"model.eta", 1}, {"model.eta", 2}}},                          // the later value wins
      {{{"model.epsilon", 1.5}}},                                      // out of range
      {{{"experiment.nu", 0.7}}},                                      // out of range, an experiment value
      {{{"stop.max_slips", 2.5}}},                                     // not whole
      {{{"stop.cycles", 3}}},                                          // not a number key: text path only
      {{{"output.every", 0.5}, {"model.epsilon", 0}}},                 // the first bad key in file order is named
      {{{"stop.time", 1e5}, {"output.every", 1}}},                     // eta * time: blames model.eta at its file line
      {{{"stop.time", 1e5}, {"output.every", 1}, {"model.eta", 20}}},  // all set: model.eta, no line
      {{{"output.every", 1e-9}}},                                      // too many samples
      {{{"solver.Ct", 1e12}}},                                         // too many reference steps
      {{{"model.alpha_b", 1.0}}},                                      // area law outside its domain
      {{{"model.epsilon", 0.5}, {"model.alpha_b", 1.0}}},  // blames the first one set of p, alpha_b, epsilon
  };
  int errors = 0;
  for (const Case& c : cases) {
    std::string label;
    std::vector<NumberSetting> settings;
    bool typed_ok = true;
    for (const auto& [k, v] : c.set) {
      label += k + "=" + io::format_double(v) + " ";
      const SceneKey* key = find_scene_key(k);
      typed_ok = typed_ok && TypedScene::settable(key, v);
      settings.push_back({key, v});
    }
    INFO(label);
    const std::string by_tree = outcome([&] {
      YAML::Node t;
      t.reset(tree);
      for (const auto& [k, v] : c.set) t.reset(apply_override(t, k, YAML::Node(io::format_double(v))));
      return scene_from_tree(t, kScene);
    });
    errors += by_tree.rfind("error: ", 0) == 0 ? 1 : 0;
    if (!typed_ok) {
      CHECK(c.set.front().first == "stop.cycles");
      continue;
    }
    CHECK(outcome([&] { return typed.with(settings); }) == by_tree);
  }
  CHECK(errors == 10);  // the cases above that are meant to fail do fail
  // A bound broken by a value the variant set names the key the file gave, at its line.
  const SceneKey* time = find_scene_key("stop.time");
  const SceneKey* every = find_scene_key("output.every");
  CHECK_THAT(outcome([&] {
               return typed.with({{time, 1e5}, {every, 1}});
             }),
             Catch::Matchers::Contains("small_scene.yaml:4: model.eta: too strong damping"));
  // The base is untouched by its variants.
  CHECK(scene_to_yaml(typed.scene()) == scene_to_yaml(scene_from_tree(tree, kScene)));
}
