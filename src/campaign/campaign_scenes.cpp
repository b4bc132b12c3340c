#include "campaign/campaign_scenes.hpp"

#include <yaml-cpp/yaml.h>

#include <map>
#include <optional>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/load.hpp"
#include "scene/scene_keys.hpp"
#include "scene/topography_cache.hpp"

namespace asperity {

namespace fs = std::filesystem;
using io::format_double;

// A scene tree error caused by an override, re-reported at the campaign line that set it.
[[noreturn]] void rethrow_at_campaign_line(const io::InputError& e, const std::string& campaign_file, int line,
                                           const std::string& key) {
  std::string msg = e.message;
  if (!e.key.empty() && e.key != key) msg = e.key + ": " + msg;
  throw io::InputError(campaign_file, line, key, msg + " (on " + e.file + ")");
}

namespace {

// Values naming files (the experiment) are relative to the campaign file; the scene loader
// resolves them against the base scene, so they are handed over as absolute paths.
bool is_path_key(const std::string& key) {
  return key == "experiment" || key == "experiment.file" || key == "topography" || key == "topography.recipe" ||
         key == "topography.file";
}

YAML::Node override_value(const std::string& key, const AxisValue& v, const fs::path& campaign_dir) {
  if (v.is_number) return YAML::Node(format_double(v.number));
  if (v.is_yaml) return YAML::Load(v.text);
  if (is_path_key(key)) return YAML::Node(fs::absolute(campaign_dir / v.text).lexically_normal().string());
  return YAML::Node(v.text);
}

// A base scene: its file's text, read once and checked by the loader, parsed again for every
// point. A fresh tree per point, because yaml-cpp merges the memory of every tree a node is
// copied into with the tree it came from: points built from one shared base tree made that
// base's memory grow with each point built, and each copy cost O(points built so far).
struct BaseScene {
  fs::path file;
  std::string text;
};

YAML::Node parse_base(const BaseScene& b) {
  try {
    return YAML::Load(b.text);  // the text passed load_scene_tree's checks when it was read
  } catch (const YAML::Exception& e) {
    throw io::InputError(io::input_path(b.file), e.mark.is_null() ? 0 : e.mark.line + 1, "",
                         "malformed YAML: " + e.msg);
  }
}

// The tree of a base scene with the campaign's `set` applied; errors name the scene file (its
// own errors) or, when `set_lines` is given, the campaign's `set` line (the override's).
YAML::Node base_tree(const Campaign& c, const BaseScene& b, const std::vector<int>* set_lines) {
  const fs::path dir = c.file.parent_path();
  YAML::Node tree = parse_base(b);
  TopographyCache* const cache = c.topography.get();
  if (set_lines) scene_from_tree(tree, b.file, cache);  // the base scene alone: its own errors first
  for (std::size_t i = 0; i < c.set.size(); ++i) {
    const auto& [key, v] = c.set[i];
    try {
      tree.reset(apply_override(tree, key, override_value(key, v, dir)));
      if (set_lines) scene_from_tree(tree, b.file, cache);
    } catch (const io::InputError& e) {
      if (!set_lines) throw;
      rethrow_at_campaign_line(e, io::input_path(c.file), (*set_lines)[i], "set." + key);
    }
  }
  return tree;
}

// Reads each base scene once (the loader's checks: a regular file, no control characters, one
// document).
std::vector<BaseScene> base_scenes(const Campaign& c) {
  std::vector<BaseScene> out;
  for (const fs::path& p : c.scenes) {
    load_scene_tree(p);
    // Read again with the same bounded reader (a file swapped since is caught, never unbounded).
    out.push_back({p, io::read_input_file(p, io::input_path(p), io::kMaxYamlBytes)});
  }
  return out;
}

}  // namespace

struct CampaignScenes::Impl {
  const Campaign* campaign = nullptr;
  std::vector<BaseScene> bases;
  bool typed_ready = false;
  std::vector<std::optional<Scene>> typed_bases;  // base scene + set, without junctions (lazy)
  // Base scene + set + a point's values that are not numbers (e.g. another experiment file),
  // converted once per distinct combination; nothing when that alone is not a valid scene.
  std::map<std::string, std::optional<TypedScene>> checked;
  std::shared_ptr<TopographyCache> topography;  // the campaign's, or this object's own
};

void check_base_scenes(const Campaign& c, const std::vector<int>& set_lines) {
  for (const BaseScene& b : base_scenes(c)) base_tree(c, b, &set_lines);
}

CampaignScenes::CampaignScenes(const Campaign& campaign) : impl_(std::make_unique<Impl>()) {
  impl_->campaign = &campaign;
  impl_->bases = base_scenes(campaign);
  impl_->topography = campaign.topography ? campaign.topography : std::make_shared<TopographyCache>();
}
CampaignScenes::~CampaignScenes() = default;
CampaignScenes::CampaignScenes(CampaignScenes&&) noexcept = default;

Scene CampaignScenes::scene(const Point& point) const {
  Impl& im = *impl_;
  const BaseScene& b = im.bases.at(point.scene);
  const fs::path dir = im.campaign->file.parent_path();
  // Numbers are set on a typed scene; the other values (paths, names) select which typed scene.
  std::vector<const PointValue*> other;
  std::vector<NumberSetting> numbers;
  bool typed = true;
  for (const PointValue& pv : point.values) {
    const SceneKey* k = find_scene_key(pv.axis->key);
    if (pv.value.is_number && TypedScene::settable(k, pv.value.number)) {
      numbers.push_back({k, pv.value.number});
      continue;
    }
    // A later value above an earlier number's key (experiment after experiment.mass) replaces it.
    for (const NumberSetting& n : numbers)
      if (std::string(n.key->name).rfind(pv.axis->key + ".", 0) == 0) typed = false;
    other.push_back(&pv);
  }
  if (typed) {
    std::string id = std::to_string(point.scene);
    for (const PointValue* pv : other) id += "\n" + pv->axis->key + "=" + pv->value.text;
    auto it = im.checked.find(id);
    if (it == im.checked.end()) {
      if (im.checked.size() >= 64) im.checked.clear();  // bounded: each holds its junctions
      std::optional<TypedScene> t;
      try {
        YAML::Node tree = base_tree(*im.campaign, b, nullptr);
        for (const PointValue* pv : other)
          tree.reset(apply_override(tree, pv->axis->key, override_value(pv->axis->key, pv->value, dir)));
        t.emplace(typed_scene_from_tree(tree, b.file, im.topography));
      } catch (const io::InputError&) {
        // Reported point by point below (the point's numbers may also make it valid).
      }
      it = im.checked.emplace(id, std::move(t)).first;
    }
    if (it->second) return it->second->with(numbers);
  }
  YAML::Node tree = base_tree(*im.campaign, b, nullptr);  // this point's own tree
  for (const PointValue& pv : point.values)
    tree.reset(apply_override(tree, pv.axis->key, override_value(pv.axis->key, pv.value, dir)));
  return scene_from_tree(tree, b.file, im.topography.get());
}

std::optional<Scene> CampaignScenes::unchecked_scene(const Point& point) const {
  Impl& im = *impl_;
  if (!im.typed_ready) {
    for (const BaseScene& b : im.bases) {
      std::optional<Scene> s;
      try {
        s = scene_from_tree(base_tree(*im.campaign, b, nullptr), b.file, im.topography.get());
        s->experiment.junctions = {};  // the hash names the data by its files' bytes
        s->experiment.measured.reset();
      } catch (const std::exception&) {
        s.reset();  // scene() reports it, point by point
      }
      im.typed_bases.push_back(std::move(s));
    }
    im.typed_ready = true;
  }
  const std::optional<Scene>& base = im.typed_bases.at(point.scene);
  if (!base) return std::nullopt;
  Scene s = *base;
  for (const PointValue& pv : point.values) {
    if (!pv.value.is_number) return std::nullopt;
    const SceneKey* k = find_scene_key(pv.axis->key);
    if (!k || k->kind != KeyKind::number) return std::nullopt;
    k->set(s, pv.value.number);
  }
  return s;
}

std::string CampaignScenes::value_text(const Scene& scene, const std::string& key) {
  return scene_value_text(scene, key);
}

}  // namespace asperity
