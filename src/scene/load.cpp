#include "scene/load.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <system_error>

#include "io/numbers.hpp"
#include "io/yaml_util.hpp"

namespace asperity {

namespace fs = std::filesystem;
using namespace scene_io;

InputError::InputError(std::string file_, int line_, std::string key_, std::string message_, int column_)
    : std::runtime_error(format(file_, line_, column_, key_, message_)),
      file(std::move(file_)),
      line(line_),
      column(column_),
      key(std::move(key_)),
      message(std::move(message_)) {}

std::string InputError::format(const std::string& file, int line, int column, const std::string& key,
                               const std::string& message) {
  std::string s = file;
  if (!file.empty() && line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  if (!key.empty()) s += (s.empty() ? "" : ": ") + key;
  s += (s.empty() ? "" : ": ") + message;
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

namespace {

const std::vector<std::string> kSceneKeys{"experiment", "model", "solver", "stop", "output"};
const std::vector<std::string> kExperimentKeys{"name", "description", "mass", "k_L", "v", "E",
                                               "nu", "sigma_exp", "junctions", "measured"};
const std::vector<std::string> kExperimentMapKeys{"file", "name", "description", "mass", "k_L",
                                                  "v", "E", "nu", "sigma_exp"};
const std::vector<std::string> kModelKeys{"eta", "epsilon", "c_min", "p", "alpha_b", "junction_shape", "area_law"};
const std::vector<std::string> kSolverKeys{"method", "Ct", "tolerance"};
const std::vector<std::string> kStopKeys{"time", "at_first_peak", "cycles", "wall_time", "max_slips"};
const std::vector<std::string> kOutputKeys{"every", "series", "peak_min_drop"};

// Limits that keep every run finite in time and memory (see check_resources).
constexpr double kMinTolerance = 1e-14;  // ≈ 45 machine epsilons
constexpr double kMaxSamples = 1e6;      // samples of one run (1e6: 0.3 GB resident, 0.1 GB of series.csv)
constexpr double kMaxEtaTime = 1e6;      // η · stop.time: ≤ ~3·10^5 steps forced by damping
constexpr double kMaxPeriods = 1e6;     // slider oscillations in stop.time (≥ 2·10^7 event steps)
constexpr double kMaxReferenceSteps = 1e9;  // steps of the reference solver
constexpr double kMaxP = 10;             // model.p
constexpr double kMinSlipAreaFraction = 1e-6;  // A_s/A0 at a junction's first slip

std::string display_path(const fs::path& p) { return p.lexically_normal().string(); }

fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p), ec);
  return ec ? fs::absolute(p).lexically_normal() : r;
}

// "must be RANGE, got X" (and " (WHY)" when given: the reason for a limit that is not obvious).
void check(bool ok, const MapView& v, const YAML::Node& n, const std::string& k, const std::string& range, double x,
           const std::string& why = "") {
  if (!ok) v.fail_at(n, k, "must be " + range + ", got " + format_double(x) + (why.empty() ? "" : " (" + why + ")"));
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
    v.fail_at(n, k, std::string(what) + " not found: " + quote(rel) + " (looked for " + display_path(p) + ")");
  if (!why.empty()) v.fail_at(n, k, std::string(what) + " " + why + ": " + display_path(p));
  return p;
}

// A value of the experiment: from the scene's experiment map when given there, else from the file.
struct Pick {
  const MapView* view = nullptr;
  YAML::Node node;
  explicit operator bool() const { return view != nullptr; }
};

Experiment load_experiment_impl(const fs::path& path, const std::string& display, const MapView* ov) {
  const YAML::Node root = load_yaml_file(path, display);
  const MapView f(Source{display, nullptr}, root, "", kExperimentKeys, 1);

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

  Experiment e;
  e.file = resolved(path);
  {
    const Pick p = required("name");
    e.name = p.view->string(p.node, "name");
    if (trim(e.name).empty()) p.view->fail_at(p.node, "name", "must not be empty");
    if (has_control_char(e.name))
      p.view->fail_at(p.node, "name", "must not hold control characters (newline, tab, ...), got " + quote(e.name));
  }
  if (const Pick p = pick("description")) e.description = p.view->string(p.node, "description");

  struct Positive {
    const char* key;
    const char* unit;
    double Experiment::*field;
  };
  for (const Positive& q : {Positive{"mass", "kg", &Experiment::mass_kg}, Positive{"k_L", "N/m", &Experiment::k_L},
                            Positive{"v", "m/s", &Experiment::v}, Positive{"E", "Pa", &Experiment::E}}) {
    const auto [p, x] = number(q.key, q.unit);
    check(x > 0, *p.view, p.node, q.key, "> 0", x);
    e.*q.field = x;
  }
  {
    const auto [p, x] = number("nu", nullptr);
    check(x > -1 && x <= 0.5, *p.view, p.node, "nu", "in (-1, 0.5]", x);
    e.nu = x;
  }
  {
    const auto [p, x] = number("sigma_exp", "Pa");
    check(x > 0, *p.view, p.node, "sigma_exp", "> 0", x);
    e.sigma_exp = x;
  }

  const fs::path base = path.parent_path();
  {
    const YAML::Node n = f.require("junctions");
    const fs::path csv = referenced_file(f, n, "junctions", base, "junctions CSV", kMaxCsvBytes);
    e.junctions_file = resolved(csv);
    e.junctions = scene_io::read_junctions_csv(csv, display_path(csv));
  }
  if (auto n = f.find("measured")) {
    const fs::path csv = referenced_file(f, *n, "measured", base, "measured CSV", kMaxCsvBytes);
    e.measured_file = resolved(csv);
    e.measured = scene_io::read_measured_csv(csv, display_path(csv));
  }
  return e;
}

// Checks across keys, once every value is known: the work a scene asks for must be bounded.
// Each error names the key the user set (the first of the pair that was given).
void check_resources(const Scene& s, const MapView& model, const MapView& stop, const MapView& output,
                     const MapView& solver) {
  auto blame = [](const MapView& a, const char* ka, const MapView& b, const char* kb) {
    if (auto n = a.find(ka)) return std::make_pair(&a, std::make_pair(std::string(ka), *n));
    if (auto n = b.find(kb)) return std::make_pair(&b, std::make_pair(std::string(kb), *n));
    return std::make_pair(&a, std::make_pair(std::string(ka), YAML::Node(YAML::NodeType::Null)));
  };
  // Samples are kept in memory (56 bytes each, twice while on the loading branch).
  const double intervals = s.stop.time / s.output.every;
  if (!(intervals <= kMaxSamples * (1 + 1e-12))) {
    const auto [v, kn] = blame(output, "every", stop, "time");
    v->fail_at(kn.second, kn.first,
               "too many samples: stop.time / output.every = " + format_short(intervals) + ", more than the " +
                   format_short(kMaxSamples) + " a run may record (output.every must be >= stop.time * 1e-6 = " +
                   format_short(s.stop.time / kMaxSamples) + " s)");
  }
  // Damping rate η forces explicit steps shorter than ~3/η on both solvers (the reference's
  // is unstable beyond η dt = 2; the event solver's Dormand–Prince stability limit is 3.3/η).
  const double eta_time = s.model.eta * s.stop.time;
  if (!(eta_time <= kMaxEtaTime)) {
    const auto [v, kn] = blame(model, "eta", stop, "time");
    v->fail_at(kn.second, kn.first,
               "too strong damping: eta * stop.time = " + format_short(eta_time) + " is more than " + format_short(kMaxEtaTime) +
                   ": damping that strong needs explicit steps shorter than ~3/eta, i.e. over " +
                   format_short(eta_time / 3.3) + " steps (the slider is overdamped long before: eta = " +
                   format_double(s.model.eta) + " 1/s, stop.time = " + format_double(s.stop.time) + " s)");
  }
  // Time scales: the slider oscillates at ω = sqrt((k_L + K0)/M) with K0 = Σ k_i(A0) =
  // E κ(1) Σ ℓ0_i (κ(1) = 1/((1+ν)(1−ν/2)) for both shapes); every solver needs several steps
  // per period (the event solver ~20, the reference C_t per T0 = 2π/sqrt(K0/M)).
  double sum_l0 = 0;
  for (const double a : s.experiment.junctions.area_m2) sum_l0 += initial_diameter(a);
  const double K0 = s.experiment.E * sum_l0 / ((1.0 + s.experiment.nu) * (1.0 - 0.5 * s.experiment.nu));
  const double M = s.experiment.mass_kg;
  const double periods = s.stop.time * std::sqrt((s.experiment.k_L + K0) / M) / (2.0 * M_PI);
  if (!(periods <= kMaxPeriods)) {
    const auto [v, kn] = blame(stop, "time", stop, "time");
    v->fail_at(kn.second, kn.first,
               "too many slider oscillations: " + format_short(periods) + " periods of 2 pi sqrt(M/(k_L + K0)) in " +
                   format_double(s.stop.time) + " s, more than " + format_short(kMaxPeriods) + " (mass = " +
                   format_double(M) + " kg, k_L = " + format_double(s.experiment.k_L) + " N/m, K0 = " + format_short(K0) +
                   " N/m)");
  }
  if (s.solver.method == SolverMethod::reference && K0 > 0) {
    const double steps = s.stop.time * s.solver.Ct / (2.0 * M_PI * std::sqrt(M / K0));
    if (!(steps <= kMaxReferenceSteps)) {
      const auto [v, kn] = blame(solver, "Ct", stop, "time");
      v->fail_at(kn.second, kn.first,
                 "too many reference steps: stop.time * Ct / T0 = " + format_short(steps) + ", more than " +
                     format_short(kMaxReferenceSteps) + " (dt = T0/Ct = " + format_short(2.0 * M_PI * std::sqrt(M / K0) / s.solver.Ct) +
                     " s)");
    }
  }
}

// The area law A = A0 − α_b f²/A0^p is used between A0 and the area at the first slip,
// A_s = A0 (1 − φ_s²). If a junction would lose all but a tiny part of its area before it
// slips, the law is far outside any measured range, 1 − φ_s² is lost to rounding (and is 0 in
// double beyond β ~ 1e15, where the solvers divide by zero), and its slip distance is tiny.
void check_area_law_domain(const Scene& s, const MapView& model) {
  if (s.model.alpha_b == 0 || s.experiment.junctions.size() == 0) return;
  const ContactLaw law = make_contact_law(s.experiment, s.model);
  const auto [lo, hi] = std::minmax_element(s.experiment.junctions.area_m2.begin(), s.experiment.junctions.area_m2.end());
  for (const double A0 : {*lo, *hi}) {  // φ_s is monotonic in A0
    const double phi = law.slip_phi(A0);
    const double kept = 1.0 - phi * phi;
    if (kept >= kMinSlipAreaFraction) continue;
    // Blame a model key the user gave: one set by --set or a sweep (no file mark) first.
    std::string key;
    for (const char* k : {"p", "alpha_b", "epsilon"})
      if (auto n = model.find(k); n && key.empty() && n->Mark().is_null()) key = k;
    for (const char* k : {"p", "alpha_b", "epsilon"})
      if (key.empty() && model.find(k)) key = k;
    const auto n = key.empty() ? std::nullopt : model.find(key);
    const std::string msg =
        "junctions of " + format_short(A0) + " m^2 would keep only " + (kept > 0 ? format_short(kept) : "nothing") +
        " of their area at their first slip (A = A0 - alpha_b f^2/A0^p with p = " + format_double(s.model.p) +
        ", alpha_b = " + format_double(s.model.alpha_b) + ", sigma = sigma_exp/epsilon = " + format_short(law.sigma) +
        " Pa; at least " + format_short(kMinSlipAreaFraction) + " is needed for the law to be meaningful)";
    if (n) model.fail_at(*n, key, msg);
    // Neither key set in the scene: the experiment (areas, sigma_exp) is what is out of range.
    throw InputError(s.experiment.junctions_file.string(), 0, "area_m2", msg);
  }
}

YAML::Node section(const MapView& root, const std::string& k) {
  auto n = root.find(k);
  return n ? *n : YAML::Node(YAML::NodeType::Null);
}

Scene scene_from_tree_impl(const YAML::Node& tree, const fs::path& origin, const std::string& display,
                           const std::vector<SetRecord>* sets) {
  const Source src{display, sets};
  const MapView root(src, tree, "", kSceneKeys, 1);
  Scene s;
  if (!origin.empty()) s.file = resolved(origin);

  // experiment: a path, or a map {file: path, value overrides...}
  {
    const YAML::Node en = root.require("experiment");
    std::optional<MapView> ov;
    const MapView* fv = &root;
    std::string fk = "experiment";
    YAML::Node fn = en;
    if (en.IsMap()) {
      ov.emplace(src, en, "experiment", kExperimentMapKeys);
      fv = &*ov;
      fk = "file";
      fn = ov->require("file");
    } else if (!en.IsScalar()) {
      root.fail_at(en, "experiment",
                   "expected the path of an experiment file or a map {file: path, ...}, got " + node_kind(en));
    }
    const fs::path p = referenced_file(*fv, fn, fk, origin.parent_path(), "experiment file", kMaxYamlBytes);
    s.experiment_ref = fn.Scalar();
    s.experiment = load_experiment_impl(p, display_path(p), ov ? &*ov : nullptr);
  }

  const MapView model_view(src, section(root, "model"), "model", kModelKeys);
  {
    const MapView& m = model_view;
    auto& x = s.model;
    if (auto n = m.find("eta")) {
      x.eta = m.number(*n, "eta", "1/s");
      check(x.eta >= 0, m, *n, "eta", ">= 0", x.eta);
    }
    if (auto n = m.find("epsilon")) {
      x.epsilon = m.number(*n, "epsilon", nullptr);
      check(x.epsilon > 0 && x.epsilon <= 1, m, *n, "epsilon", "in (0, 1]", x.epsilon);
    }
    if (auto n = m.find("c_min")) {
      x.c_min = m.number(*n, "c_min", nullptr);
      check(x.c_min > 0 && x.c_min < 1, m, *n, "c_min", "in (0, 1)", x.c_min);
    }
    if (auto n = m.find("p")) {
      x.p = m.number(*n, "p", nullptr);
      check(x.p >= 0 && x.p <= kMaxP, m, *n, "p", "in [0, 10]", x.p,
            "A0^(p+1) must stay a normal double for areas in [1e-20, 1] m^2");
    }
    if (auto n = m.find("alpha_b")) {
      x.alpha_b = m.number(*n, "alpha_b", "m^(2p+2)/N^2");
      check(x.alpha_b >= 0, m, *n, "alpha_b", ">= 0", x.alpha_b);
    }
    if (auto n = m.find("junction_shape"))
      x.junction_shape = m.enumeration<JunctionShape>(*n, "junction_shape",
                                       {{"elliptic", JunctionShape::elliptic}, {"circular", JunctionShape::circular}});
    if (auto n = m.find("area_law"))
      x.area_law = m.enumeration<AreaLaw>(*n, "area_law", {{"until_first_slip", AreaLaw::until_first_slip}, {"always", AreaLaw::always}});
  }
  const MapView solver_view(src, section(root, "solver"), "solver", kSolverKeys);
  {
    const MapView& m = solver_view;
    auto& x = s.solver;
    if (auto n = m.find("method"))
      x.method = m.enumeration<SolverMethod>(*n, "method", {{"reference", SolverMethod::reference}, {"event", SolverMethod::event}});
    if (auto n = m.find("Ct")) {
      x.Ct = m.number(*n, "Ct", nullptr);
      check(x.Ct >= 1, m, *n, "Ct", ">= 1", x.Ct, "reference steps per T0; fewer is unstable for any scene");
    }
    if (auto n = m.find("tolerance")) {
      x.tolerance = m.number(*n, "tolerance", nullptr);
      check(x.tolerance >= kMinTolerance && x.tolerance <= 0.1, m, *n, "tolerance", "in [1e-14, 0.1]", x.tolerance,
            "relative error per step; below ~50 machine epsilons the error control only chases rounding and "
            "the steps shrink without bound");
    }
  }
  const MapView stop_view(src, section(root, "stop"), "stop", kStopKeys);
  {
    const MapView& m = stop_view;
    auto& x = s.stop;
    if (auto n = m.find("time")) {
      x.time = m.number(*n, "time", "s");
      check(x.time > 0, m, *n, "time", "> 0", x.time);
    }
    if (auto n = m.find("at_first_peak")) x.at_first_peak = m.boolean(*n, "at_first_peak");
    if (auto n = m.find("cycles")) {
      x.cycles = m.integer(*n, "cycles");
      if (x.cycles != -1 && x.cycles < 1)
        m.fail_at(*n, "cycles", "must be -1 (never) or >= 1, got " + std::to_string(x.cycles));
    }
    if (auto n = m.find("wall_time")) {
      x.wall_time = m.number(*n, "wall_time", "s");
      check(x.wall_time > 0, m, *n, "wall_time", "> 0", x.wall_time, "seconds of wall-clock time for one run");
    }
    if (auto n = m.find("max_slips")) {
      const double k = m.number(*n, "max_slips", nullptr);
      check(k >= 1 && k <= 1e18 && k == std::floor(k), m, *n, "max_slips", "a whole number in [1, 1e18]", k);
      x.max_slips = static_cast<std::int64_t>(k);
    }
  }
  const MapView output_view(src, section(root, "output"), "output", kOutputKeys);
  {
    const MapView& m = output_view;
    auto& x = s.output;
    if (auto n = m.find("every")) {
      x.every = m.number(*n, "every", "s");
      check(x.every > 0, m, *n, "every", "> 0", x.every);
    }
    if (auto n = m.find("series")) {
      x.series = m.string_list(*n, "series");
      const auto& all = all_series();
      for (std::size_t i = 0; i < x.series.size(); ++i) {
        const std::string& name = x.series[i];
        const YAML::Node item = (*n)[i];
        const YAML::Node at = item.Mark().is_null() ? *n : item;
        if (std::find(all.begin(), all.end(), name) == all.end())
          m.fail_at(at, "series", "unknown series " + quote(name) + did_you_mean(name, all) + "; valid: " + join(all));
        if (std::find(x.series.begin(), x.series.begin() + static_cast<std::ptrdiff_t>(i), name) !=
            x.series.begin() + static_cast<std::ptrdiff_t>(i))
          m.fail_at(at, "series", "series " + quote(name) + " listed twice");
      }
    }
    if (auto n = m.find("peak_min_drop")) {
      x.peak_min_drop = m.number(*n, "peak_min_drop", nullptr);
      check(x.peak_min_drop > 0 && x.peak_min_drop < 1, m, *n, "peak_min_drop", "in (0, 1)", x.peak_min_drop);
    }
  }
  check_resources(s, model_view, stop_view, output_view, solver_view);
  check_area_law_domain(s, model_view);
  return s;
}

std::vector<std::string> split_key(const std::string& dotted, const std::string& where) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = dotted.find('.', start);
    parts.push_back(dotted.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    const std::string& p = parts.back();
    const bool ok = !p.empty() && std::all_of(p.begin(), p.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    });
    if (!ok)
      throw InputError(where, 0, dotted, "malformed key (expected names joined by dots, e.g. model.eta)");
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

// Path copy: a new map for every level along `parts`, sharing all other nodes (and their Marks).
YAML::Node set_path(const YAML::Node& node, const std::vector<std::string>& parts, std::size_t i,
                    const YAML::Node& value, const std::string& where, const std::string& dotted) {
  const std::string here = [&] {
    std::string s;
    for (std::size_t j = 0; j < i; ++j) s += (j ? "." : "") + parts[j];
    return s;
  }();
  YAML::Node cur = node;
  if (cur.IsDefined() && cur.IsScalar() && here == "experiment") {  // path → {file: path}
    YAML::Node m(YAML::NodeType::Map);
    m[YAML::Node("file")] = cur;
    cur.reset(m);  // rebind: `cur = m` would turn the caller's (shared) node into the map
  }
  if (cur.IsDefined() && !cur.IsNull() && !cur.IsMap())
    throw InputError(where, 0, dotted, "cannot set " + dotted + ": " + (here.empty() ? "the scene" : here) +
                                           " is " + node_kind(cur) + ", not a map");
  auto child_value = [&](const YAML::Node& old) {
    return i + 1 == parts.size() ? value : set_path(old, parts, i + 1, value, where, dotted);
  };
  YAML::Node out(YAML::NodeType::Map);
  bool replaced = false;
  if (cur.IsDefined() && cur.IsMap()) {
    for (auto it = cur.begin(); it != cur.end(); ++it) {
      if (!replaced && it->first.IsScalar() && it->first.Scalar() == parts[i]) {
        out[it->first] = child_value(it->second);  // keeps the original key node (and its line)
        replaced = true;
      } else {
        out[it->first] = it->second;
      }
    }
  }
  if (!replaced) out[YAML::Node(parts[i])] = child_value(YAML::Node(YAML::NodeType::Null));
  return out;
}

YAML::Node apply_override_impl(const YAML::Node& tree, const std::string& dotted, const YAML::Node& value,
                               const std::string& where) {
  const std::vector<std::string> parts = split_key(dotted, where);
  if (!value.IsDefined()) throw InputError(where, 0, dotted, "undefined value");
  return set_path(tree, parts, 0, strip_marks(value), where, dotted);
}

}  // namespace

Experiment load_experiment(const fs::path& yaml, const YAML::Node* overrides) {
  const std::string display = display_path(yaml);
  if (!overrides) return load_experiment_impl(yaml, display, nullptr);
  const MapView ov(Source{"overrides of " + display, nullptr}, *overrides, "experiment", kExperimentMapKeys);
  return load_experiment_impl(yaml, display, &ov);
}

YAML::Node load_scene_tree(const fs::path& yaml) { return load_yaml_file(yaml, display_path(yaml)); }

YAML::Node apply_override(YAML::Node scene_tree, const std::string& dotted_key, const YAML::Node& value) {
  return apply_override_impl(scene_tree, dotted_key, value, "override " + dotted_key);
}

Scene scene_from_tree(const YAML::Node& tree, const fs::path& origin_file) {
  return scene_from_tree_impl(tree, origin_file, display_path(origin_file), nullptr);
}

Scene load_scene(const fs::path& yaml, const std::vector<std::string>& overrides) {
  const std::string display = display_path(yaml);
  YAML::Node tree = load_yaml_file(yaml, display);
  std::vector<SetRecord> sets;
  for (const std::string& o : overrides) {
    const std::string where = "--set " + o;
    const std::size_t eq = o.find('=');
    if (eq == std::string::npos) throw InputError(where, 0, "", "expected key=value, e.g. --set model.eta=50");
    const std::string key(trim(std::string_view(o).substr(0, eq)));
    const YAML::Node value = load_yaml_text(o.substr(eq + 1), where, key);
    if (value.IsNull()) throw InputError(where, 0, key, "missing value after '=' (write \"\" for empty text)");
    tree = apply_override_impl(tree, key, value, where);
    sets.push_back({key, where});
  }
  return scene_from_tree_impl(tree, yaml, display, &sets);
}

}  // namespace asperity
