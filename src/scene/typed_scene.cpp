#include "scene/typed_scene.hpp"

#include <cmath>

#include "io/input_error.hpp"
#include "scene/topography_cache.hpp"
#include "scene/topography_junctions.hpp"
#include "scene/validate.hpp"

namespace asperity {

namespace {

// The origins of a variant: the tree's keys, plus the keys the variant set (no file line).
class VariantOrigins final : public KeyOrigins {
 public:
  VariantOrigins(const std::string& display, const std::map<std::string, int>& lines,
                 const std::vector<NumberSetting>& settings)
      : display_(display), lines_(lines), settings_(settings) {}
  bool given(const std::string& dotted) const override { return set_here(dotted) || lines_.count(dotted) > 0; }
  bool overridden(const std::string& dotted) const override {
    if (set_here(dotted)) return true;
    const auto it = lines_.find(dotted);
    return it != lines_.end() && it->second == 0;
  }
  [[noreturn]] void fail(const std::string& dotted, const std::string& message) const override {
    const auto it = lines_.find(dotted);
    const int line = set_here(dotted) || it == lines_.end() ? 0 : it->second;
    throw io::InputError(display_, line, dotted, message);
  }

 private:
  bool set_here(const std::string& dotted) const {
    for (const NumberSetting& s : settings_)
      if (dotted == s.key->name) return true;
    return false;
  }
  const std::string& display_;
  const std::map<std::string, int>& lines_;
  const std::vector<NumberSetting>& settings_;
};

}  // namespace

TypedScene::TypedScene(Scene scene, std::string display_file, std::map<std::string, int> given_lines,
                       std::shared_ptr<TopographyCache> topography)
    : scene_(std::move(scene)),
      display_(std::move(display_file)),
      lines_(std::move(given_lines)),
      topography_(std::move(topography)) {}

bool TypedScene::settable(const SceneKey* key, double value) {
  return key && key->kind == KeyKind::number && std::isfinite(value);
}

Scene TypedScene::with(const std::vector<NumberSetting>& settings) const {
  Scene s = scene_;
  bool recipe_changed = false;
  // The loader checks keys in table order: the first bad one in that order is the one reported.
  for (const SceneKey& k : scene_keys()) {
    const NumberSetting* last = nullptr;
    for (const NumberSetting& st : settings)
      if (st.key == &k) last = &st;
    if (!last) continue;
    if (!settable(last->key, last->value)) throw std::logic_error(std::string("TypedScene: cannot set ") + k.name);
    // A value set from outside the file has no line: the loader names the scene file alone.
    if (!k.allowed(last->value)) throw io::InputError(display_, 0, k.name, out_of_range_message(k, last->value));
    const std::string name = k.name;
    // A topography scene's experiment is its recipe's: set the recipe, never the experiment
    // (scene.yaml writes the recipe, so an experiment value set here would not be repeated).
    if (name.rfind("topography.", 0) == 0) {
      if (!s.topography)
        throw io::InputError(display_, 0, name, "the scene has no topography section (its junctions come from a file)");
      if (name.rfind("topography.self_affine.", 0) == 0 && s.topography->kind != TopographyKind::self_affine)
        throw io::InputError(display_, 0, name, "the scene's topography is not self_affine");
      recipe_changed = true;
    } else if (s.topography && name.rfind("experiment.", 0) == 0) {
      throw io::InputError(display_, 0, name,
                           "a topography scene's experiment comes from its recipe: set topography.* instead");
    }
    k.set(s, last->value);
  }
  if (recipe_changed) {
    if (const auto p = topography_recipe_problem(*s.topography)) throw io::InputError(display_, 0, p->key, p->message);
    const TopographyRecipe& r = *s.topography;
    s.experiment = topography_experiment(r, *topography_contact(r, topography_.get()), scene_made_by(r));
  }
  validate_scene(s, VariantOrigins(display_, lines_, settings));
  return s;
}

}  // namespace asperity
