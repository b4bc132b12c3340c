#include "scene/load.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/warnings.hpp"
#include "io/yaml_util.hpp"
#include "scene/override.hpp"
#include "scene/scene_keys.hpp"
#include "scene/topography_cache.hpp"
#include "scene/topography_recipe_load.hpp"
#include "scene/validate.hpp"

namespace asperity {

namespace fs = std::filesystem;
using io::did_you_mean;
using io::has_control_char;
using io::input_file_problem;
using io::join;
using io::kMaxCsvBytes;
using io::kMaxYamlBytes;
using io::load_yaml_file;
using io::load_yaml_text;
using io::MapView;
using io::node_kind;
using io::quote;
using io::SetRecord;
using io::Source;
using io::trim;

namespace {

// Keys a section may hold: the key table's (scene_keys.hpp), in its order.
std::vector<std::string> leaves(const std::string& section) {
  std::vector<std::string> out;
  for (const SceneKey& k : scene_keys())
    if (k.section() == section) out.push_back(k.leaf());
  return out;
}

const std::vector<std::string> kSceneKeys{"experiment", "topography", "model", "solver", "stop", "output"};
const std::vector<std::string> kExperimentMapKeys = leaves("experiment");
const std::vector<std::string> kExperimentKeys = [] {  // the experiment file's: its data, not the path
  std::vector<std::string> k(kExperimentMapKeys.begin() + 1, kExperimentMapKeys.end());
  k.insert(k.end(), {"junctions", "measured"});
  return k;
}();
// A scene's experiment map may give its data inline instead of a file (Scene.from_dict).
const std::vector<std::string> kExperimentInlineKeys = [] {
  std::vector<std::string> k = kExperimentMapKeys;
  k.insert(k.end(), {"junctions", "measured"});
  return k;
}();

fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

// "must be RANGE, got X (WHY)" when x is outside the key's range; a warning when it is allowed
// but outside the plausible range (the one place, for files and --set alike).
void check(const SceneKey& key, double x, const MapView& v, const YAML::Node& n, const std::string& k) {
  if (!key.allowed(x)) v.fail_at(n, k, out_of_range_message(key, x));
  if (const std::string why = implausible_message(key, x); !why.empty()) v.warn_at(n, k, why);
}

// A file named by `k` (value node n, read by view v), relative to base_dir; must be a regular
// file of at most max_bytes (refused here, at the line that names it, before anything reads it).
fs::path referenced_file(const MapView& v, const YAML::Node& n, const std::string& k, const fs::path& base_dir,
                         const char* what, std::uintmax_t max_bytes) {
  const std::string rel = v.string(n, k);
  if (trim(rel).empty()) v.fail_at(n, k, std::string("empty path (expected ") + what + ")");
  const fs::path p = base_dir / fs::path(rel);
  const std::string why = input_file_problem(p, max_bytes);
  if (why == "file not found")
    v.fail_at(n, k, std::string(what) + " not found: " + quote(rel) + " (looked for " + io::input_path(p) + ")");
  if (!why.empty()) v.fail_at(n, k, std::string(what) + " " + why + ": " + io::input_path(p));
  return p;
}

// A value of the experiment: from the scene's experiment map when given there, else from the file.
struct Pick {
  const MapView* view = nullptr;
  YAML::Node node;
  explicit operator bool() const { return view != nullptr; }
};

// A column given inline, checked value by value with the CSV reader's rules and words
// (scene/csv.hpp), each error naming the value, e.g. area_m2[3].
std::vector<double> inline_column(const MapView& v, const std::string& k, const char* unit,
                                  std::string (*problem)(double)) {
  const YAML::Node list = v.require(k);
  if (!list.IsSequence()) v.fail_at(list, k, "expected a list of numbers, got " + node_kind(list));
  std::vector<double> out;
  out.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string ki = k + "[" + std::to_string(i) + "]";
    const YAML::Node item = list[i];
    const double x = v.number(item, ki, unit);
    if (const std::string why = problem(x); !why.empty()) v.fail_at(item, ki, why);
    out.push_back(x);
  }
  return out;
}

// Junction columns given inline, {area_m2: [...], x_m: [...], y_m: [...]}, as a junctions CSV's.
JunctionPopulation inline_junctions(const MapView& ev, const YAML::Node& n) {
  if (!n.IsMap())
    ev.fail_at(n, "junctions", "expected a map {area_m2: [...], x_m: [...], y_m: [...]}, got " + node_kind(n));
  const MapView jv(ev.source(), n, ev.key("junctions"), {"area_m2", "x_m", "y_m"});
  auto column = [&](const std::string& k, const char* unit, std::string (*problem)(double)) {
    return inline_column(jv, k, unit, problem);
  };
  JunctionPopulation p;
  p.area_m2 = column("area_m2", "m^2", junction_area_problem);
  if (p.area_m2.empty()) jv.fail_at(jv.require("area_m2"), "area_m2", "must hold at least one junction's area");
  const auto x = jv.find("x_m"), y = jv.find("y_m");
  if (x.has_value() != y.has_value())
    jv.fail_at(n, x ? "y_m" : "x_m", "x_m and y_m must be given together (or neither)");
  if (x) {
    p.x_m = column("x_m", "m", junction_coordinate_problem);
    p.y_m = column("y_m", "m", junction_coordinate_problem);
    for (const auto& [k, c] : {std::pair{"x_m", &p.x_m}, std::pair{"y_m", &p.y_m}})
      if (c->size() != p.area_m2.size())
        jv.fail_at(*jv.find(k), k,
                   "has " + std::to_string(c->size()) + " values, area_m2 has " + std::to_string(p.area_m2.size()) +
                       " (one per junction)");
  }
  return p;
}

// A measured curve given inline, {Q_N: [...], A_m2: [...]}, as a measured CSV's.
MeasuredCurve inline_measured(const MapView& ev, const YAML::Node& n) {
  if (!n.IsMap()) ev.fail_at(n, "measured", "expected a map {Q_N: [...], A_m2: [...]}, got " + node_kind(n));
  const MapView mv(ev.source(), n, ev.key("measured"), {"Q_N", "A_m2"});
  MeasuredCurve m;
  m.Q_N = inline_column(mv, "Q_N", "N", measured_force_problem);
  m.A_m2 = inline_column(mv, "A_m2", "m^2", measured_area_problem);
  if (m.Q_N.size() != m.A_m2.size())
    mv.fail_at(*mv.find("A_m2"), "A_m2",
               "has " + std::to_string(m.A_m2.size()) + " values, Q_N has " + std::to_string(m.Q_N.size()) +
                   " (one per sample)");
  return m;
}

// `path` empty: the experiment is given whole in the scene's map `ov`, its data inline (node
// `junctions`, and `measured` when the map has one).
Experiment load_experiment_impl(const fs::path& path, const std::string& display, const MapView* ov,
                                const YAML::Node* junctions = nullptr) {
  std::optional<MapView> file_view;
  if (!path.empty()) file_view.emplace(Source{display, nullptr}, load_yaml_file(path, display), "", kExperimentKeys, 1);
  const MapView& f = file_view ? *file_view : *ov;

  auto pick = [&](const std::string& k) -> Pick {
    if (ov)
      if (auto n = ov->find(k)) return {ov, *n};
    if (auto n = f.find(k)) return {&f, *n};
    return {};
  };
  auto required = [&](const std::string& k) -> Pick {
    Pick p = pick(k);
    if (!p) p = {&f, f.require(k)};  // throws "missing required key"
    return p;
  };
  auto number = [&](const std::string& k, const char* unit) {
    const Pick p = required(k);
    return std::make_pair(p, p.view->number(p.node, k, unit));
  };

  Scene holder;  // the key table sets fields of a Scene
  Experiment& e = holder.experiment;
  if (!path.empty()) e.file = resolved(path);
  {
    const Pick p = required("name");
    e.name = p.view->string(p.node, "name");
    if (trim(e.name).empty()) p.view->fail_at(p.node, "name", "must not be empty");
    if (has_control_char(e.name))
      p.view->fail_at(p.node, "name", "must not hold control characters (newline, tab, ...), got " + quote(e.name));
  }
  if (const Pick p = pick("description")) e.description = p.view->string(p.node, "description");

  for (const SceneKey& k : scene_keys()) {
    if (k.kind != KeyKind::number || k.section() != "experiment") continue;
    const std::string leaf = k.leaf();
    const auto [p, x] = number(leaf, k.unit);
    check(k, x, *p.view, p.node, leaf);
    k.set(holder, x);
  }
  if (!file_view) {
    e.junctions = inline_junctions(*ov, *junctions);
    if (const auto n = ov->find("measured")) e.measured = inline_measured(*ov, *n);
    return std::move(e);
  }
  const fs::path base = path.parent_path();
  {
    const YAML::Node n = f.require("junctions");
    const fs::path csv = referenced_file(f, n, "junctions", base, "junctions CSV", kMaxCsvBytes);
    e.junctions_file = resolved(csv);
    e.junctions = read_junctions_csv(csv, io::input_path(csv));
  }
  if (auto n = f.find("measured")) {
    const fs::path csv = referenced_file(f, *n, "measured", base, "measured CSV", kMaxCsvBytes);
    e.measured_file = resolved(csv);
    e.measured = read_measured_csv(csv, io::input_path(csv));
  }
  return std::move(e);
}

// Where the values of a tree's model, solver, stop and output keys come from (validate.hpp), and
// of an inline experiment's (a key of a section the tree lacks is not given).
class TreeOrigins final : public KeyOrigins {
 public:
  explicit TreeOrigins(const std::vector<MapView>& sections) : sections_(sections) {}
  bool given(const std::string& dotted) const override {
    for (const MapView& v : sections_)
      if (dotted.compare(0, v.path().size() + 1, v.path() + ".") == 0) return node(dotted).has_value();
    return false;
  }
  bool overridden(const std::string& dotted) const override {
    const auto n = node(dotted);
    return n && n->Mark().is_null();
  }
  [[noreturn]] void fail(const std::string& dotted, const std::string& message) const override {
    const auto n = node(dotted);
    view(dotted).fail_at(n ? *n : YAML::Node(YAML::NodeType::Null), leaf(dotted), message);
  }

 private:
  static std::string leaf(const std::string& dotted) { return dotted.substr(dotted.find('.') + 1); }
  const MapView& view(const std::string& dotted) const {
    for (const MapView& v : sections_)
      if (dotted.compare(0, v.path().size() + 1, v.path() + ".") == 0) return v;
    throw std::logic_error("no section for " + dotted);
  }
  std::optional<YAML::Node> node(const std::string& dotted) const { return view(dotted).find(leaf(dotted)); }
  const std::vector<MapView>& sections_;
};

// A key of the table that is not a plain number, read from its node.
void read_other(const MapView& m, const YAML::Node& n, const SceneKey& key, Scene& s) {
  const std::string k = key.leaf();
  const std::string name = key.name;
  if (name == "model.junction_shape")
    s.model.junction_shape = m.enumeration<JunctionShape>(
        n, k, {{"elliptic", JunctionShape::elliptic}, {"circular", JunctionShape::circular}});
  else if (name == "model.area_law")
    s.model.area_law =
        m.enumeration<AreaLaw>(n, k, {{"until_first_slip", AreaLaw::until_first_slip}, {"always", AreaLaw::always}});
  else if (name == "model.interactions")
    s.model.interactions =
        m.enumeration<Interactions>(n, k, {{"none", Interactions::none}, {"elastic", Interactions::elastic}});
  else if (name == "model.interaction_weighting")
    s.model.interaction_weighting = m.enumeration<TractionWeighting>(
        n, k, {{"uniform", TractionWeighting::uniform}, {"rigid", TractionWeighting::rigid}});
  else if (name == "solver.method")
    s.solver.method =
        m.enumeration<SolverMethod>(n, k, {{"reference", SolverMethod::reference}, {"event", SolverMethod::event}});
  else if (name == "stop.at_first_peak")
    s.stop.at_first_peak = m.boolean(n, k);
  else if (name == "stop.cycles") {
    s.stop.cycles = m.integer(n, k);
    if (s.stop.cycles != -1 && s.stop.cycles < 1)
      m.fail_at(n, k, "must be -1 (never) or >= 1, got " + std::to_string(s.stop.cycles));
  } else if (name == "output.series") {
    auto& series = s.output.series;
    series = m.string_list(n, k);
    const auto& all = all_series();
    for (std::size_t i = 0; i < series.size(); ++i) {
      const std::string& id = series[i];
      const YAML::Node item = n[i];
      const YAML::Node at = item.Mark().is_null() ? n : item;
      if (std::find(all.begin(), all.end(), id) == all.end())
        m.fail_at(at, k, "unknown series " + quote(id) + did_you_mean(id, all) + "; valid: " + join(all));
      if (std::find(series.begin(), series.begin() + static_cast<std::ptrdiff_t>(i), id) !=
          series.begin() + static_cast<std::ptrdiff_t>(i))
        m.fail_at(at, k, "series " + quote(id) + " listed twice");
    }
  } else {
    throw std::logic_error("scene key without a reader: " + name);
  }
}

YAML::Node section(const MapView& root, const std::string& k) {
  auto n = root.find(k);
  return n ? *n : YAML::Node(YAML::NodeType::Null);
}

// origin: the scene file (empty: a scene given in memory); relative paths resolve against base_dir.
// A scene's `topography:` (a recipe file's path, or a map: the recipe inline or {recipe: path,
// values replaced}) → its recipe, and the experiment of its contact (through `cache` when given).
void read_topography(const MapView& root, const YAML::Node& tn, const fs::path& base_dir, TopographyCache* cache,
                     Scene& s) {
  if (const auto en = root.find("experiment"))
    root.fail_at(*en, "experiment", "give either experiment or topography (which makes the experiment), not both");
  TopographyRecipe r;
  if (tn.IsScalar()) {
    const fs::path p = referenced_file(root, tn, "topography", base_dir, "topography recipe", kMaxYamlBytes);
    r = load_topography_recipe(p);
  } else if (tn.IsMap()) {
    r = topography_recipe_from_scene(root.source(), tn, base_dir);
  } else {
    root.fail_at(tn, "topography",
                 "expected the path of a topography recipe or a map of its keys, got " + node_kind(tn));
  }
  std::shared_ptr<const TopographyContact> contact;
  try {
    contact = topography_contact(r, cache);
  } catch (const io::InputError& e) {
    // What the solve finds in the scene's own section (the contact at the map's edge, a junction
    // out of range) may come of a value a --set gave: named as a key's own check names it (the
    // --set, or the section's line), not as the scene without a line.
    if (e.file != root.source().file || e.column != 0) throw;
    io::fail(root.source(), tn, e.key, e.message, e.line);
  }
  s.experiment = topography_experiment(r, *contact, scene_made_by(r));
  s.topography = std::move(r);
}

Scene scene_from_tree_impl(const YAML::Node& tree, const fs::path& origin, const fs::path& base_dir,
                           const std::string& display, const std::vector<SetRecord>* sets, TopographyCache* cache) {
  io::HeldWarnings warnings;  // said once the scene is accepted: a refused one says its error alone
  const Source src{display, sets, &scene_key_names()};
  const MapView root(src, tree, "", kSceneKeys, origin.empty() ? 0 : 1);  // a tree in memory has no lines
  Scene s;
  if (!origin.empty()) s.file = resolved(origin);

  std::optional<MapView> inline_experiment;  // a scene's experiment with its junctions inline
  if (const auto tn = root.find("topography")) {
    read_topography(root, *tn, base_dir, cache, s);
  } else {  // experiment: a path, or a map {file: path, value overrides...}
    const YAML::Node en = root.require("experiment");
    std::optional<MapView> ov;
    const MapView* fv = &root;
    std::string fk = "experiment";
    YAML::Node fn = en;
    std::optional<YAML::Node> inline_junctions;
    if (en.IsMap()) {
      // With a file, its data come from there (junctions or measured here: unknown keys, as before).
      ov.emplace(src, en, "experiment", en["file"].IsDefined() ? kExperimentMapKeys : kExperimentInlineKeys);
      fv = &*ov;
      fk = "file";
      inline_junctions = ov->find("junctions");
      if (!inline_junctions) {
        if (const auto m = ov->find("measured")) ov->fail_at(*m, "measured", "needs the junctions inline too");
        fn = ov->require("file");
      }
    } else if (!en.IsScalar()) {
      root.fail_at(en, "experiment",
                   "expected the path of an experiment file or a map {file: path, ...}, got " + node_kind(en));
    }
    if (inline_junctions) {
      s.experiment = load_experiment_impl({}, display, &*ov, &*inline_junctions);
      inline_experiment = ov;
    } else {
      const fs::path p = referenced_file(*fv, fn, fk, base_dir, "experiment file", kMaxYamlBytes);
      s.experiment_ref = fn.Scalar();
      s.experiment = load_experiment_impl(p, io::input_path(p), ov ? &*ov : nullptr);
    }
  }

  // model, solver, stop, output: every key of the table, in its order (the first bad one is reported).
  std::vector<MapView> views;
  views.reserve(4);
  for (const char* sec : {"model", "solver", "stop", "output"}) {
    const MapView& m = views.emplace_back(src, section(root, sec), sec, leaves(sec));  // checks its keys first
    for (const SceneKey& k : scene_keys()) {
      if (k.section() != m.path()) continue;
      const auto n = m.find(k.leaf());
      if (!n) continue;
      if (k.kind != KeyKind::number) {
        read_other(m, *n, k, s);
        continue;
      }
      const double x = m.number(*n, k.leaf(), k.unit);
      check(k, x, m, *n, k.leaf());
      k.set(s, x);
    }
  }
  if (inline_experiment) views.push_back(*inline_experiment);  // its junctions' overlaps name experiment.junctions
  validate_scene(s, TreeOrigins(views));
  warnings.release();
  return s;
}

}  // namespace

Experiment load_experiment(const fs::path& yaml, const YAML::Node* overrides) {
  const std::string display = io::input_path(yaml);
  io::HeldWarnings warnings;  // said once the experiment is accepted
  std::optional<MapView> ov;
  if (overrides) ov.emplace(Source{"overrides of " + display, nullptr}, *overrides, "experiment", kExperimentMapKeys);
  Experiment e = load_experiment_impl(yaml, display, ov ? &*ov : nullptr);
  warnings.release();
  return e;
}

YAML::Node load_scene_tree(const fs::path& yaml) { return load_yaml_file(yaml, io::input_path(yaml)); }

Scene scene_from_tree(const YAML::Node& tree, const fs::path& origin_file, TopographyCache* topography) {
  return scene_from_tree_impl(tree, origin_file, origin_file.parent_path(), io::input_path(origin_file), nullptr,
                              topography);
}

Scene scene_from_memory(const YAML::Node& tree, const fs::path& base_dir, const std::string& display) {
  return scene_from_tree_impl(tree, {}, base_dir, display, nullptr, nullptr);
}

TypedScene typed_scene_from_tree(const YAML::Node& tree, const fs::path& origin_file,
                                 std::shared_ptr<TopographyCache> topography) {
  Scene s = scene_from_tree(tree, origin_file, topography.get());
  // The line of each key's value (of its key when the value is empty), as MapView::fail_at names it.
  auto line_of = [](const YAML::Node& n) { return n.IsDefined() && !n.Mark().is_null() ? n.Mark().line + 1 : 0; };
  std::map<std::string, int> lines;
  for (const char* sec : {"experiment", "model", "solver", "stop", "output"}) {
    const YAML::Node n = tree[sec];
    if (!n.IsDefined() || !n.IsMap()) continue;
    for (auto it = n.begin(); it != n.end(); ++it)
      if (it->first.IsScalar())
        lines[std::string(sec) + "." + it->first.Scalar()] =
            it->second.IsDefined() && !it->second.IsNull() ? line_of(it->second) : line_of(it->first);
  }
  return TypedScene(std::move(s), io::input_path(origin_file), std::move(lines), std::move(topography));
}

Scene load_scene(const fs::path& yaml, const std::vector<std::string>& overrides, const std::string& override_label) {
  const std::string display = io::input_path(yaml);
  YAML::Node tree = load_yaml_file(yaml, display);
  std::vector<SetRecord> sets;
  for (const std::string& o : overrides) {
    const std::string where = override_label + " " + o;
    const std::size_t eq = o.find('=');
    if (eq == std::string::npos)
      throw io::InputError(where, 0, "", "expected key=value, e.g. " + override_label + " model.eta=50");
    const std::string key(trim(std::string_view(o).substr(0, eq)));
    const YAML::Node value = load_yaml_text(o.substr(eq + 1), where, key);
    if (value.IsNull()) throw io::InputError(where, 0, key, "missing value after '=' (write \"\" for empty text)");
    tree = apply_override_at(tree, key, value, where);
    sets.push_back({key, where});
  }
  return scene_from_tree_impl(tree, yaml, yaml.parent_path(), display, &sets, nullptr);
}

}  // namespace asperity
