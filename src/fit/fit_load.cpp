#include "fit/fit_load.hpp"
#include "fit/fit_load_optimizer.hpp"
#include "scene/csv.hpp"
#include "scene/load.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <system_error>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/scene_keys.hpp"

namespace asperity {

namespace fs = std::filesystem;
using io::did_you_mean;
using io::format_double;
using io::join;
using io::load_yaml_file;
using io::MapView;
using io::node_kind;
using io::quote;
using io::Source;

namespace {

const std::vector<std::string> kFitKeys{"name",        "description", "objective", "separate",
                                        "experiments", "parameters",  "optimizer", "profile",
                                        "error_bars",  "noise",       "intervals", "force_score"};
const std::vector<std::string> kExperimentKeys{"scene", "set", "target", "force"};
const std::vector<std::string> kNoiseKeys{"area", "force", "stick_slip"};
const std::vector<std::string> kIntervalKeys{"hessian_step", "bootstrap", "bootstrap_seed"};
const std::vector<std::string> kTargetKeys{"drop", "period"};
const std::vector<std::string> kParameterKeys{"lo", "hi", "start", "scale", "per_experiment"};
const std::vector<std::string> kProfileKeys{"parameter", "span", "points"};

// Units of the numeric scene keys, for messages ("1.6 MPa" → "expected a plain number in Pa").
const char* unit_of(const std::string& key) {
  const SceneKey* k = find_scene_key(key);
  return k ? k->unit : nullptr;
}

bool all_names_ok(const std::string& s) {
  return !s.empty() && s != "." && s != ".." && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
}

// Forced settings per objective (see fit_load.hpp), applied after the user's `set`.
std::vector<std::pair<std::string, std::string>> forced_settings(FitObjective o, bool series) {
  if (o == FitObjective::user) {  // the scene's own stop; every series column when the caller reads them
    std::string all;
    for (const std::string& c : all_series()) all += (all.empty() ? "" : ", ") + c;
    return {{"output.series", series ? "[" + all + "]" : "[]"}};
  }
  if (o == FitObjective::stick_slip)
    return {{"output.series", "[]"}, {"stop.at_first_peak", "false"}, {"stop.cycles", "5"}};
  if (o == FitObjective::area_and_force)  // stop.time and output.every follow the measured Q(t): read_experiment
    return {{"output.series", "[Q]"}, {"stop.at_first_peak", "false"}, {"stop.cycles", "-1"}};
  return {{"output.series", "[]"}, {"stop.at_first_peak", "true"}};
}

double positive(const MapView& v, const YAML::Node& n, const std::string& k, const char* unit) {
  const double x = v.number(n, k, unit);
  if (!(x > 0)) v.fail_at(n, k, "must be > 0, got " + format_double(x));
  return x;
}

struct ParamNodes {  // where each parameter's values were written (for errors found later)
  YAML::Node key, lo, hi, start;
};

// What the fit's top-level keys name: name, description, objective, separate, force_score.
void read_fit_header(const MapView& root, const fs::path& path, const FitLoadOptions& options, FitSpec& spec) {
  if (auto n = root.find("name")) {
    spec.name = root.string(*n, "name");
    if (!all_names_ok(spec.name))
      root.fail_at(*n, "name", "must be a folder name (letters, digits, '_', '-', '.'), got " + quote(spec.name));
  } else {
    spec.name = path.empty() ? std::string("fit") : path.stem().string();
  }
  if (auto n = root.find("description")) spec.description = root.string(*n, "description");
  if (options.user_objective) {
    if (auto n = root.find("objective"))
      root.fail_at(*n, "objective",
                   "the objective is the caller's own (" + options.user_objective_name +
                       "); remove this key, or give no objective of your own");
    spec.objective = FitObjective::user;
  } else {
    YAML::Node objective_node = root.require("objective");
    spec.objective = root.enumeration<FitObjective>(objective_node, "objective",
                                                    {{"quadratic_alpha", FitObjective::quadratic_alpha},
                                                     {"area_curve", FitObjective::area_curve},
                                                     {"stick_slip", FitObjective::stick_slip},
                                                     {"area_and_force", FitObjective::area_and_force}});
  }
  if (auto n = root.find("separate")) spec.separate = root.boolean(*n, "separate");
  if (auto n = root.find("force_score")) {
    if (spec.objective != FitObjective::area_and_force)
      root.fail_at(*n, "force_score",
                   std::string("a Q(t) score is used by the area_and_force objective only, not ") +
                       objective_name(spec.objective));
    spec.force_score = root.enumeration<ForceScore>(*n, "force_score",
                                                    {{"pointwise", ForceScore::pointwise},
                                                     {"loading_and_cycles", ForceScore::loading_and_cycles},
                                                     {"loading_and_peaks", ForceScore::loading_and_peaks},
                                                     {"auto", ForceScore::automatic}});
  }
}

// One free parameter `key` from its map {lo:, hi:, start:, scale:, per_experiment:}.
FitParameter read_parameter(const Source& src, const MapView& params, const std::string& key, const YAML::Node& node,
                            const FitSpec& spec, ParamNodes& nodes) {
  const MapView p(src, node, params.key(key), kParameterKeys);
  if (!node.IsMap()) params.fail_at(node, key, "expected a map {lo:, hi:, start:}, got " + node_kind(node));
  FitParameter fp;
  fp.key = key;
  nodes.lo = p.require("lo"), nodes.hi = p.require("hi"), nodes.start = p.require("start");
  const char* unit = unit_of(key);
  fp.lo = p.number(nodes.lo, "lo", unit);
  fp.hi = p.number(nodes.hi, "hi", unit);
  fp.start = p.number(nodes.start, "start", unit);
  if (!(fp.lo < fp.hi))
    p.fail_at(nodes.hi, "hi", "must be > lo = " + format_double(fp.lo) + ", got " + format_double(fp.hi));
  if (!(fp.start >= fp.lo && fp.start <= fp.hi))
    p.fail_at(nodes.start, "start",
              "must be in [lo, hi] = [" + format_double(fp.lo) + ", " + format_double(fp.hi) + "], got " +
                  format_double(fp.start));
  if (auto s = p.find("scale")) {
    fp.log_scale = p.enumeration<bool>(*s, "scale", {{"linear", false}, {"log", true}});
    if (fp.log_scale && !(fp.lo > 0))
      p.fail_at(*s, "scale", "log scale needs lo > 0, got lo = " + format_double(fp.lo));
  }
  if (auto s = p.find("per_experiment")) {
    fp.per_experiment = p.boolean(*s, "per_experiment");
    if (fp.per_experiment && spec.separate)
      p.fail_at(*s, "per_experiment",
                "has no effect with separate: true (every parameter is then per experiment); remove it");
  }
  return fp;
}

// `parameters:` into spec.parameters; where each one's values were written.
std::vector<ParamNodes> read_parameters(const Source& src, const MapView& root, FitSpec& spec) {
  std::vector<ParamNodes> pnodes;
  const YAML::Node pn = root.require("parameters");
  if (!pn.IsMap() || pn.size() == 0)
    root.fail_at(
        pn, "parameters",
        "expected a map of free parameters, e.g. {model.alpha_b: {lo: 1e-16, hi: 3e-15, start: 7.25e-16}}, got " +
            node_kind(pn));
  const MapView params(src, pn, "parameters", numeric_scene_keys());
  for (auto it = pn.begin(); it != pn.end(); ++it) {
    ParamNodes nodes{it->first, {}, {}, {}};
    spec.parameters.push_back(read_parameter(src, params, it->first.Scalar(), it->second, spec, nodes));
    pnodes.push_back(nodes);
  }
  return pnodes;
}

// An entry of `experiments:` as written: a scene path, or a map {scene:, set:, target:}.
struct ExperimentEntry {
  YAML::Node scene_node;
  std::optional<MapView> view;                                // the map form's
  std::vector<std::pair<std::string, std::string>> fixed;     // settings, in order
  std::vector<std::pair<std::string, YAML::Node>> set_nodes;  // where each `set` key was written
  StickSlipTarget target;
  bool has_target = false;
};

ExperimentEntry read_entry(const Source& src, const MapView& root, const YAML::Node& en, std::size_t i,
                           const FitSpec& spec) {
  const YAML::Node item = en[i];
  const std::string ikey = "experiments[" + std::to_string(i) + "]";
  ExperimentEntry x;
  if (item.IsScalar()) {
    x.scene_node = item;
    return x;
  }
  if (!item.IsMap())
    root.fail_at(item.Mark().is_null() ? en : item, ikey,
                 "expected a scene path or a map {scene: path, set: {...}}, got " + node_kind(item));
  MapView& ev = x.view.emplace(src, item, ikey, kExperimentKeys);
  x.scene_node = ev.require("scene");
  if (auto s = ev.find("set")) {
    if (!s->IsMap())
      ev.fail_at(*s, "set", "expected a map of dotted scene keys, e.g. {model.eta: 50}, got " + node_kind(*s));
    for (auto it = s->begin(); it != s->end(); ++it) {
      if (!it->first.IsScalar()) ev.fail_at(it->first, "set", "keys must be dotted scene keys");
      const std::string k = it->first.Scalar();
      if (std::any_of(spec.parameters.begin(), spec.parameters.end(),
                      [&](const FitParameter& p) { return p.key == k; }))
        ev.fail_at(it->first, "set." + k, "is a free parameter of this fit; it cannot also be set");
      YAML::Emitter out;
      out << YAML::Flow << it->second;
      x.fixed.emplace_back(k, out.c_str());
      x.set_nodes.emplace_back(k, it->first);
    }
  }
  if (auto t = ev.find("target")) {
    if (spec.objective != FitObjective::stick_slip && spec.objective != FitObjective::area_and_force)
      ev.fail_at(*t, "target",
                 std::string("stick-slip targets are used by the stick_slip and area_and_force objectives only, not ") +
                     objective_name(spec.objective));
    const MapView tv(src, *t, ev.key("target"), kTargetKeys);
    x.target.drop_N = positive(tv, tv.require("drop"), "drop", "N");
    x.target.period_s = positive(tv, tv.require("period"), "period", "s");
    x.has_target = true;
  }
  return x;
}

// The measured A(Q) curve an objective needs, checked; an error is located at the experiment
// file's `measured:` line, the key the user would fix.
void check_measured(const Scene& scene, const std::string& name, const FitSpec& spec, const MapView& sv,
                    const YAML::Node& scene_node, const std::string& skey, const std::string& display) {
  const bool needs_measured = spec.objective == FitObjective::quadratic_alpha ||
                              spec.objective == FitObjective::area_curve ||
                              spec.objective == FitObjective::area_and_force;
  if (!needs_measured) return;
  if (!scene.experiment.measured)
    sv.fail_at(scene_node, skey,
               std::string("objective ") + objective_name(spec.objective) +
                   " needs a measured A(Q) curve, and experiment " + quote(name) + " (" +
                   io::input_path(scene.experiment.file) + ") has none (key `measured`)");
  double A0_sum = 0;
  for (const double a : scene.experiment.junctions.area_m2) A0_sum += a;
  const std::string why = measured_curve_problem(*scene.experiment.measured, A0_sum);
  if (why.empty()) return;
  const fs::path& ef = scene.experiment.file;
  const std::string edisplay = io::input_path(ef);
  int line = 0;
  try {
    const YAML::Node m = load_yaml_file(ef, edisplay)["measured"];
    if (m.IsDefined()) line = m.Mark().line + 1;
  } catch (const std::exception&) {
    // the file was read a moment ago; without it the message keeps no line
  }
  throw io::InputError(edisplay, line, "measured",
                       why + " (" + io::input_path(scene.experiment.measured_file) + ", experiment " + quote(name) +
                           " of " + display + ")");
}

// Every value the optimizer may try must make a valid scene: the bounds checked on `fe`.
void check_bounds(const Source& src, const MapView& root, const FitSpec& spec, const std::vector<ParamNodes>& pnodes,
                  const FitExperiment& fe) {
  for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
    const FitParameter& p = spec.parameters[j];
    for (const auto& [which, x, node] : {std::tuple{"lo", p.lo, pnodes[j].lo}, std::tuple{"hi", p.hi, pnodes[j].hi}}) {
      try {
        fe.scene.build({{p.key, x}});
      } catch (const io::InputError& e) {
        const MapView pv(src, root.require("parameters")[p.key], "parameters." + p.key, kParameterKeys);
        pv.fail_at(node, which, "invalid for experiment " + quote(fe.name) + ": " + e.message);
      }
    }
  }
}

// Where a fit's experiments resolve their scenes and what they add to them.
struct ExperimentContext {
  const Source& src;
  const MapView& root;
  const fs::path& base;
  const std::string& display;
  const std::vector<std::string>& overrides;
  const FitLoadOptions& options;
};

// The measured Q(t) of experiment i (`force:`, read from `force_file`), which the area_and_force
// objective needs and no other takes.
std::optional<MeasuredForce> read_experiment_force(const ExperimentContext& cx, const ExperimentEntry& x,
                                                   const YAML::Node& en, std::size_t i, const FitSpec& spec,
                                                   fs::path& force_file) {
  const MapView& sv = x.view ? *x.view : cx.root;
  const std::string skey = x.view ? "scene" : "experiments[" + std::to_string(i) + "]";
  if (const auto fn = x.view ? x.view->find("force") : std::nullopt) {
    if (spec.objective != FitObjective::area_and_force)
      x.view->fail_at(*fn, "force",
                      std::string("a measured Q(t) is used by the area_and_force objective only, not ") +
                          objective_name(spec.objective));
    const std::string frel = x.view->string(*fn, "force");
    force_file = cx.base / fs::path(frel);
    std::error_code e3;
    const auto st = fs::status(force_file, e3);
    if (!fs::exists(st))
      x.view->fail_at(*fn, "force",
                      "force CSV not found: " + quote(frel) + " (looked for " + io::input_path(force_file) + ")");
    if (!fs::is_regular_file(st))
      x.view->fail_at(*fn, "force", "force CSV is not a regular file: " + io::input_path(force_file));
    return read_force_csv(force_file, io::input_path(force_file));
  }
  if (spec.objective == FitObjective::area_and_force)
    sv.fail_at(
        en[i], x.view ? "force" : skey,
        "the area_and_force objective needs force: CSV of the measured Q(t) (columns t_s, Q_N) for every experiment");
  return std::nullopt;
}

// Experiment i of `experiments:` (en): its scene template with every setting, checked.
FitExperiment read_experiment(const ExperimentContext& cx, const YAML::Node& en, std::size_t i, const FitSpec& spec,
                              const std::vector<ParamNodes>& pnodes) {
  ExperimentEntry x = read_entry(cx.src, cx.root, en, i, spec);
  const MapView& sv = x.view ? *x.view : cx.root;
  const std::string skey = x.view ? "scene" : "experiments[" + std::to_string(i) + "]";
  const std::string rel = sv.string(x.scene_node, skey);
  const fs::path scene_path = cx.base / fs::path(rel);
  {
    std::error_code e2;
    const auto st = fs::status(scene_path, e2);
    if (!fs::exists(st))
      sv.fail_at(x.scene_node, skey,
                 "scene file not found: " + quote(rel) + " (looked for " + io::input_path(scene_path) + ")");
    if (fs::is_directory(st))
      sv.fail_at(x.scene_node, skey, "scene file is a directory: " + io::input_path(scene_path));
  }
  if (spec.objective == FitObjective::stick_slip && !x.has_target)
    sv.fail_at(en[i], x.view ? "target" : skey,
               "the stick_slip objective needs target: {drop: N, period: s} for every experiment");
  fs::path force_file;
  std::optional<MeasuredForce> force = read_experiment_force(cx, x, en, i, spec, force_file);
  if (!cx.overrides.empty()) {                   // before the objective's forced settings, which win
    (void)load_scene(scene_path, cx.overrides);  // each --set checked on this scene, with its message
    for (const std::string& o : cx.overrides) {
      const std::size_t eq = o.find('=');
      x.fixed.emplace_back(o.substr(0, eq), eq == std::string::npos ? "" : o.substr(eq + 1));
    }
  }
  for (const auto& f : forced_settings(spec.objective, cx.options.user_series)) x.fixed.push_back(f);
  if (force) {  // run to the last measured time, sampled at least as finely as the measured Q(t)
    double dt_min = force->t_s.back() - force->t_s.front();
    for (std::size_t k = 1; k < force->t_s.size(); ++k) dt_min = std::min(dt_min, force->t_s[k] - force->t_s[k - 1]);
    double every = dt_min;
    try {
      every = std::min(dt_min, SceneTemplate::load(scene_path, x.fixed).build().output.every);
    } catch (const io::InputError&) {
      // reported with its location by the load below
    }
    x.fixed.emplace_back("stop.time", format_double(force->t_s.back()));
    x.fixed.emplace_back("output.every", format_double(every));
  }
  FitExperiment fe;
  fe.target = x.target;
  fe.force = std::move(force);
  fe.force_file = force_file;
  Scene base_scene;
  try {
    fe.scene = SceneTemplate::load(scene_path, x.fixed);
    base_scene = fe.scene.build();
  } catch (const io::InputError& e) {
    // A value from `set` carries no line of the scene file: name the fit file's line.
    for (const auto& [k, kn] : x.set_nodes)
      if (e.line == 0 && (e.key == k || e.key.rfind(k + ".", 0) == 0 || k.rfind(e.key, 0) == 0))
        x.view->fail_at(kn, "set." + k, e.message);
    throw;
  }
  fe.name = base_scene.experiment.name;
  if (std::any_of(spec.experiments.begin(), spec.experiments.end(),
                  [&](const FitExperiment& o) { return o.name == fe.name; }))
    sv.fail_at(x.scene_node, skey, "experiment " + quote(fe.name) + " is listed twice (outputs are named after it)");
  check_measured(base_scene, fe.name, spec, sv, x.scene_node, skey, cx.display);
  check_bounds(cx.src, cx.root, spec, pnodes, fe);
  return fe;
}

// `profile:` (a flag, or a map {parameter:, span:, points:}) into spec.
void read_profile(const Source& src, const MapView& root, FitSpec& spec) {
  const auto pn = root.find("profile");
  if (!pn) return;
  if (pn->IsScalar()) {
    spec.profile = root.boolean(*pn, "profile");
    return;
  }
  const MapView p(src, *pn, "profile", kProfileKeys);
  if (auto n = p.find("parameter")) {  // a key, a list of keys, or `all`
    std::vector<std::string> wanted;
    if (n->IsSequence()) {
      wanted = p.string_list(*n, "parameter");
    } else if (p.string(*n, "parameter") == "all") {
      for (const auto& q : spec.parameters) wanted.push_back(q.key);
    } else {
      wanted.push_back(p.string(*n, "parameter"));
    }
    if (wanted.empty())
      p.fail_at(*n, "parameter", "expected a free parameter, a list of them, or all; got an empty list");
    spec.profile_settings.parameters.clear();
    for (const std::string& k : wanted) {
      const auto it = std::find_if(spec.parameters.begin(), spec.parameters.end(),
                                   [&](const FitParameter& q) { return q.key == k; });
      if (it == spec.parameters.end()) {
        std::vector<std::string> keys;
        for (const auto& q : spec.parameters) keys.push_back(q.key);
        p.fail_at(*n, "parameter",
                  "not a free parameter of this fit: " + quote(k) + did_you_mean(k, keys) + "; free: " + join(keys) +
                      " (or all)");
      }
      const auto idx = static_cast<std::size_t>(it - spec.parameters.begin());
      if (std::find(spec.profile_settings.parameters.begin(), spec.profile_settings.parameters.end(), idx) ==
          spec.profile_settings.parameters.end())
        spec.profile_settings.parameters.push_back(idx);
    }
    spec.profile_settings.parameter = spec.profile_settings.parameters.front();
  }
  if (auto n = p.find("span")) {
    spec.profile_settings.span = p.number(*n, "span", nullptr);
    if (!(spec.profile_settings.span > 0 && spec.profile_settings.span < 1))
      p.fail_at(*n, "span", "must be in (0, 1) (relative), got " + format_double(spec.profile_settings.span));
  }
  if (auto n = p.find("points")) {
    spec.profile_settings.points = p.integer(*n, "points");
    if (spec.profile_settings.points < 3 || spec.profile_settings.points > 201)
      p.fail_at(*n, "points", "must be in [3, 201], got " + std::to_string(spec.profile_settings.points));
  }
}

// `error_bars:` into spec, each nominal ± bar checked to give a valid scene for every experiment.
void read_error_bars(const Source& src, const MapView& root, FitSpec& spec) {
  const auto bn = root.find("error_bars");
  if (!bn) return;
  const MapView b(src, *bn, "error_bars", numeric_scene_keys());
  if (!bn->IsMap()) return;
  for (auto it = bn->begin(); it != bn->end(); ++it) {
    const std::string k = it->first.Scalar();
    if (std::any_of(spec.parameters.begin(), spec.parameters.end(), [&](const FitParameter& p) { return p.key == k; }))
      b.fail_at(it->first, k, "is a free parameter of this fit; it has no error bar to propagate");
    ErrorBar eb{k, positive(b, it->second, k, unit_of(k))};
    for (const auto& e : spec.experiments) {
      const double nominal = scene_value(e.scene.build(), k);
      for (const double x : {nominal - eb.bar, nominal + eb.bar}) {
        try {
          e.scene.build({{k, x}});
        } catch (const io::InputError& err) {
          b.fail_at(it->second, k,
                    "nominal ± bar gives an invalid scene for experiment " + quote(e.name) + ": " + err.message);
        }
      }
    }
    spec.error_bars.push_back(eb);
  }
}

// A relative noise level, in [kNoiseMin, kNoiseMax] (fit_load.hpp says why).
double noise_level(const MapView& v, const YAML::Node& n, const std::string& k) {
  const double x = v.number(n, k, nullptr);
  if (!(x >= kNoiseMin && x <= kNoiseMax))
    v.fail_at(n, k,
              "must be in [" + format_double(kNoiseMin) + ", " + format_double(kNoiseMax) + "] (relative), got " +
                  format_double(x));
  return x;
}

// `noise:` (area_and_force only) and `intervals:` into spec.
void read_noise_and_intervals(const Source& src, const MapView& root, FitSpec& spec) {
  if (const auto nn = root.find("noise")) {
    if (spec.objective != FitObjective::area_and_force)
      root.fail_at(*nn, "noise",
                   std::string("noise levels are used by the area_and_force objective only, not ") +
                       objective_name(spec.objective));
    const MapView nv(src, *nn, "noise", kNoiseKeys);
    if (!nn->IsMap())
      root.fail_at(*nn, "noise", "expected a map {area: 0.002, force: 0.002, stick_slip: 0.05}, got " + node_kind(*nn));
    if (auto n = nv.find("area")) spec.noise.area = noise_level(nv, *n, "area");
    if (auto n = nv.find("force")) spec.noise.force = noise_level(nv, *n, "force");
    if (auto n = nv.find("stick_slip")) spec.noise.stick_slip = noise_level(nv, *n, "stick_slip");
  }
  spec.intervals = spec.objective == FitObjective::area_and_force;
  if (const auto in = root.find("intervals")) {
    if (in->IsScalar()) {
      spec.intervals = root.boolean(*in, "intervals");
    } else {
      const MapView iv(src, *in, "intervals", kIntervalKeys);
      spec.intervals = true;
      if (auto n = iv.find("hessian_step")) {
        spec.hessian_step = iv.number(*n, "hessian_step", nullptr);
        if (!(spec.hessian_step > 0 && spec.hessian_step <= 0.2))
          iv.fail_at(*n, "hessian_step",
                     "must be in (0, 0.2] (relative step of each parameter), got " + format_double(spec.hessian_step));
      }
      if (auto n = iv.find("bootstrap")) {
        spec.bootstrap_draws = iv.integer(*n, "bootstrap");
        if (spec.bootstrap_draws != 0 && (spec.bootstrap_draws < kBootstrapMin || spec.bootstrap_draws > kBootstrapMax))
          iv.fail_at(*n, "bootstrap",
                     "must be 0 (none) or in [" + std::to_string(kBootstrapMin) + ", " + std::to_string(kBootstrapMax) +
                         "] synthetic data sets, got " + std::to_string(spec.bootstrap_draws));
      }
      if (auto n = iv.find("bootstrap_seed")) spec.bootstrap_seed = iv.seed(*n, "bootstrap_seed");
    }
    if (spec.intervals && spec.objective != FitObjective::area_and_force)
      root.fail_at(*in, "intervals",
                   std::string("statistical intervals need a chi-square objective (area_and_force), not ") +
                       objective_name(spec.objective));
  }
}

// The fit tree `root_node` (a file's, or one given in memory: `path` empty) → FitSpec; relative
// scene paths resolve against `base`, errors name `display`. The keys are read in file-format
// order, so the first error reported stays the same.
FitSpec fit_from_tree(const YAML::Node& root_node, const fs::path& path, const fs::path& base,
                      const std::string& display, const std::vector<std::string>& overrides,
                      const FitLoadOptions& options) {
  const Source src{display, nullptr};
  const MapView root(src, root_node, "", kFitKeys, path.empty() ? 0 : 1);  // a tree in memory has no lines
  FitSpec spec;
  spec.base_dir =
      base.empty() ? fs::current_path() : fs::absolute(base).lexically_normal();  // "f.yaml": its folder is ""
  if (!path.empty()) {
    std::error_code ec;
    spec.file = fs::weakly_canonical(fs::absolute(path), ec);
    if (ec) spec.file = fs::absolute(path).lexically_normal();
  }
  read_fit_header(root, path, options, spec);
  const std::vector<ParamNodes> pnodes = read_parameters(src, root, spec);
  const YAML::Node en = root.require("experiments");
  if (!en.IsSequence() || en.size() == 0)
    root.fail_at(en, "experiments", "expected a non-empty list of scene files, got " + node_kind(en));
  const ExperimentContext cx{src, root, base, display, overrides, options};
  for (std::size_t i = 0; i < en.size(); ++i) spec.experiments.push_back(read_experiment(cx, en, i, spec, pnodes));
  const YAML::Node algorithm_node = read_optimizer(src, root, spec);
  check_algorithm_accepts(spec, root, algorithm_node, display);
  read_profile(src, root, spec);
  read_error_bars(src, root, spec);
  read_noise_and_intervals(src, root, spec);
  return spec;
}

}  // namespace

FitSpec load_fit(const fs::path& path, const std::vector<std::string>& overrides, const FitLoadOptions& options) {
  const std::string display = io::input_path(path);
  return fit_from_tree(load_yaml_file(path, display), path, path.parent_path(), display, overrides, options);
}

FitSpec fit_from_memory(const YAML::Node& tree, const fs::path& base_dir, const std::string& display,
                        const std::vector<std::string>& overrides, const FitLoadOptions& options) {
  FitSpec spec = fit_from_tree(tree, {}, base_dir, display, overrides, options);
  YAML::Emitter out;
  out << tree;
  spec.memory_text = out.c_str();
  return spec;
}

}  // namespace asperity
