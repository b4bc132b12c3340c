#include "generate/recipe.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"

namespace asperity {

std::uint64_t experiment_seed(const StandinRecipe& r, std::size_t i) {
  return io::splitmix64(r.seed + static_cast<std::uint64_t>(i));
}

std::uint64_t noise_seed(std::uint64_t experiment_seed) {
  return io::splitmix64(experiment_seed ^ 0x6e6f697365ULL);  // "noise"
}

std::uint64_t positions_seed(std::uint64_t experiment_seed) {
  return io::splitmix64(experiment_seed ^ 0x706f736974696f6eull);
}

std::uint64_t force_seed(std::uint64_t experiment_seed) { return io::splitmix64(experiment_seed ^ 0x666f726365ULL); }

namespace {

using io::MapView;
using io::Source;

// Number with a range check, reported at the value's line.
double positive(const MapView& m, const std::string& k, const char* unit) {
  const YAML::Node n = m.require(k);
  const double x = m.number(n, k, unit);
  if (!(x > 0.0)) m.fail_at(n, k, "must be > 0, got " + io::format_double(x));
  return x;
}

void get_positive(const MapView& m, const std::string& k, double& out, const char* unit) {
  if (auto n = m.find(k)) {
    out = m.number(*n, k, unit);
    if (!(out > 0.0)) m.fail_at(*n, k, "must be > 0, got " + io::format_double(out));
  }
}

void get_fraction(const MapView& m, const std::string& k, double& out) {
  if (auto n = m.find(k)) {
    out = m.number(*n, k, nullptr);
    if (!(out > 0.0 && out < 1.0)) m.fail_at(*n, k, "must be between 0 and 1, got " + io::format_double(out));
  }
}

std::uint64_t seed_value(const MapView& m, const std::string& k) { return m.seed(m.require(k), k); }

// The `family` entry of a distribution map, if it is there and a scalar ("" otherwise).
std::string peek_family(const YAML::Node& n) {
  if (!n.IsMap()) return "";
  for (auto it = n.begin(); it != n.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == "family" && it->second.IsScalar()) return it->second.Scalar();
  return "";
}

const std::vector<std::string> families{"power_law", "lognormal", "fixed", "mixture"};

std::vector<std::string> keys_of(const std::string& family, bool with_weight) {
  std::vector<std::string> k{"family"};
  if (with_weight) k.push_back("weight");
  if (family == "power_law") k.insert(k.end(), {"tau", "a_min", "a_max"});
  if (family == "lognormal") k.insert(k.end(), {"median", "sigma_ln", "a_min", "a_max"});
  if (family == "fixed") k.push_back("area");
  if (family == "mixture" && !with_weight) k.push_back("components");
  return k;
}

std::vector<std::string> all_keys(bool with_weight) {
  std::vector<std::string> k;
  for (const auto& f : families)
    for (const auto& x : keys_of(f, with_weight))
      if (std::find(k.begin(), k.end(), x) == k.end()) k.push_back(x);
  return k;
}

Component read_component(const MapView& m, const std::string& family) {
  if (family == "power_law") {
    PowerLaw d;
    const YAML::Node tn = m.require("tau");
    d.tau = m.number(tn, "tau", nullptr);
    d.a_min = positive(m, "a_min", "m^2");
    const YAML::Node hn = m.require("a_max");
    d.a_max = m.number(hn, "a_max", "m^2");
    if (!(d.a_max > d.a_min)) m.fail_at(hn, "a_max", "must be > a_min");
    return d;
  }
  if (family == "lognormal") {
    LogNormal d;
    d.median = positive(m, "median", "m^2");
    d.sigma_ln = positive(m, "sigma_ln", nullptr);
    get_positive(m, "a_min", d.a_min, "m^2");
    if (auto hn = m.find("a_max")) {
      d.a_max = m.number(*hn, "a_max", "m^2");
      if (!(d.a_max > d.a_min)) m.fail_at(*hn, "a_max", "must be > a_min");
    }
    return d;
  }
  Fixed d;
  d.area = positive(m, "area", "m^2");
  return d;
}

Distribution read_distribution(const Source& src, const YAML::Node& node, const std::string& path) {
  const std::string fam = peek_family(node);
  const bool known = std::find(families.begin(), families.end(), fam) != families.end();
  // An unknown family is reported at `family` (with a suggestion), not at its parameters.
  MapView m(src, node, path, known ? keys_of(fam, false) : all_keys(false));
  const YAML::Node fn = m.require("family");
  m.enumeration<int>(fn, "family", {{"power_law", 0}, {"lognormal", 1}, {"fixed", 2}, {"mixture", 3}});
  if (fam != "mixture")
    return Distribution{std::visit([](const auto& d) { return std::variant<PowerLaw, LogNormal, Fixed, Mixture>(d); },
                                   read_component(m, fam))};

  Mixture mix;
  const YAML::Node list = m.require("components");
  if (!list.IsSequence() || list.size() == 0)
    m.fail_at(list, "components",
              "expected a non-empty list of {weight, family, ...} maps, got " + io::node_kind(list));
  for (std::size_t j = 0; j < list.size(); ++j) {
    const YAML::Node c = list[j];
    const std::string cpath = m.key("components") + "[" + std::to_string(j) + "]";
    const std::string cf = peek_family(c);
    const bool ck = cf == "power_law" || cf == "lognormal" || cf == "fixed";
    MapView cm(src, c, cpath, ck ? keys_of(cf, true) : all_keys(true));
    const YAML::Node cfn = cm.require("family");
    cm.enumeration<int>(cfn, "family", {{"power_law", 0}, {"lognormal", 1}, {"fixed", 2}});
    mix.weights.push_back(positive(cm, "weight", nullptr));
    mix.components.push_back(read_component(cm, cf));
  }
  return Distribution{mix};
}

// masses_kg: a non-empty list, increasing.
void read_masses(const MapView& top, StandinRecipe& r) {
  const YAML::Node ml = top.require("masses_kg");
  if (!ml.IsSequence() || ml.size() == 0)
    top.fail_at(ml, "masses_kg", "expected a non-empty list of masses in kg, got " + io::node_kind(ml));
  for (std::size_t i = 0; i < ml.size(); ++i) {
    const std::string k = "masses_kg[" + std::to_string(i) + "]";
    const YAML::Node n = ml[i];
    const YAML::Node at = n.Mark().is_null() ? ml : n;
    if (!n.IsScalar()) top.fail_at(at, k, "expected a number in SI units (kg), got " + io::node_kind(n));
    const double M = top.number(n, k, "kg");
    if (!(M > 0.0)) top.fail_at(at, k, "must be > 0");
    if (!r.masses_kg.empty() && !(M > r.masses_kg.back()))
      top.fail_at(at, k, "masses must be listed in increasing order");
    r.masses_kg.push_back(M);
  }
}

// The section `positions`, if any: a square or a contact disc, not both.
void read_positions(const Source& src, const MapView& top, StandinRecipe& r) {
  if (auto pn = top.find("positions")) {
    MapView p(src, *pn, "positions", {"square_side_m", "contact_radius_m", "reference_load_N"});
    if (p.find("square_side_m")) r.square_side_m = positive(p, "square_side_m", "m");
    if (p.find("contact_radius_m")) r.contact_radius_m = positive(p, "contact_radius_m", "m");
    if (p.find("reference_load_N")) r.contact_reference_load_N = positive(p, "reference_load_N", "N");
    if ((r.square_side_m > 0) == (r.contact_radius_m > 0))
      p.fail_at(*pn, "positions", "give either square_side_m or contact_radius_m (with optional reference_load_N)");
  }
}

// The section `measured`: how the measured A(Q) curves are made.
void read_measured(const Source& src, const MapView& top, StandinRecipe& r) {
  MapView m(src, top.require("measured"), "measured",
            {"alpha_b", "area_drop_smallest_load", "area_drop_largest_load", "points", "noise_relative"});
  r.alpha_b = positive(m, "alpha_b", "m^5/N^2");
  get_fraction(m, "area_drop_smallest_load", r.drop_smallest);
  get_fraction(m, "area_drop_largest_load", r.drop_largest);
  if (auto n = m.find("points")) {
    r.points = m.integer(*n, "points");
    if (r.points < 2) m.fail_at(*n, "points", "must be at least 2");
  }
  if (auto n = m.find("noise_relative")) {
    r.noise_relative = m.number(*n, "noise_relative", nullptr);
    if (!(r.noise_relative >= 0.0 && r.noise_relative < 0.1)) m.fail_at(*n, "noise_relative", "must be in [0, 0.1)");
  }
}

// The section `measured_force`, if any: how the measured Q(t) curves are made.
void read_measured_force(const Source& src, const MapView& top, StandinRecipe& r) {
  if (auto fn = top.find("measured_force")) {
    MapView m(src, *fn, "measured_force", {"every", "after_peak", "noise_relative"});
    r.force_every = positive(m, "every", "s");
    if (auto n = m.find("after_peak")) {
      r.force_after_peak = m.number(*n, "after_peak", nullptr);
      if (!(r.force_after_peak > 0.0 && r.force_after_peak <= 10.0)) m.fail_at(*n, "after_peak", "must be in (0, 10]");
    }
    if (auto n = m.find("noise_relative")) {
      r.force_noise_relative = m.number(*n, "noise_relative", nullptr);
      if (!(r.force_noise_relative >= 0.0 && r.force_noise_relative < 0.1))
        m.fail_at(*n, "noise_relative", "must be in [0, 0.1)");
    }
  }
}

// The sections `model_run` (the model runs the curves are made from) and `scenes` (the scenes
// written), if any.
void read_runs(const Source& src, const MapView& top, StandinRecipe& r) {
  if (auto rn = top.find("model_run")) {
    MapView m(src, *rn, "model_run", {"solver", "stop_time", "every", "peak_min_drop"});
    if (auto sn = m.find("solver")) {
      MapView s(src, *sn, "model_run.solver", {"method", "Ct", "tolerance"});
      if (auto n = s.find("method"))
        r.solver.method = s.enumeration<SolverMethod>(
            *n, "method", {{"reference", SolverMethod::reference}, {"event", SolverMethod::event}});
      get_positive(s, "Ct", r.solver.Ct, nullptr);
      get_positive(s, "tolerance", r.solver.tolerance, nullptr);
    }
    get_positive(m, "stop_time", r.run_stop_time, "s");
    get_positive(m, "every", r.run_every, "s");
    get_fraction(m, "peak_min_drop", r.run_peak_min_drop);
  }
  if (auto sn = top.find("scenes")) {
    MapView m(src, *sn, "scenes", {"stop_time", "every"});
    get_positive(m, "stop_time", r.scene_stop_time, "s");
    get_positive(m, "every", r.scene_every, "s");
  }
}

}  // namespace

StandinRecipe load_recipe(const std::filesystem::path& path) {
  const std::string display = io::input_path(path);
  const YAML::Node root = io::load_yaml_file(path, display);
  const Source src{display, nullptr};
  StandinRecipe r;
  r.file = path;
  MapView top(src, root, "",
              {"seed", "gravity", "masses_kg", "k_L", "v", "E", "nu", "sigma_exp", "junctions_per_newton",
               "distribution", "positions", "measured", "measured_force", "model_run", "scenes"});
  r.seed = seed_value(top, "seed");
  get_positive(top, "gravity", r.gravity, "m/s^2");
  read_masses(top, r);
  r.k_L = positive(top, "k_L", "N/m");
  r.v = positive(top, "v", "m/s");
  r.E = positive(top, "E", "Pa");
  {
    const YAML::Node n = top.require("nu");
    r.nu = top.number(n, "nu", nullptr);
    if (!(r.nu >= 0.0 && r.nu <= 0.5)) top.fail_at(n, "nu", "must be in [0, 0.5]");
  }
  r.sigma_exp = positive(top, "sigma_exp", "Pa");
  r.junctions_per_newton = positive(top, "junctions_per_newton", "1/N");
  r.distribution = read_distribution(src, top.require("distribution"), "distribution");
  read_positions(src, top, r);
  read_measured(src, top, r);
  read_measured_force(src, top, r);
  read_runs(src, top, r);
  return r;
}

}  // namespace asperity
