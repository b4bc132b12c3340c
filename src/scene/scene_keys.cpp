#include "scene/scene_keys.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "io/numbers.hpp"
#include "scene/load.hpp"

namespace asperity {

namespace {

constexpr double kRequired = std::numeric_limits<double>::quiet_NaN();

const char* name_of(JunctionShape s) { return s == JunctionShape::circular ? "circular" : "elliptic"; }
const char* name_of(AreaLaw a) { return a == AreaLaw::always ? "always" : "until_first_slip"; }
const char* name_of(Interactions i) { return i == Interactions::elastic ? "elastic" : "none"; }
const char* name_of(TractionWeighting w) { return w == TractionWeighting::rigid ? "rigid" : "uniform"; }
// The recipe of a topography scene; any other scene has none to read or set.
const TopographyRecipe& recipe_of(const Scene& s) {
  if (!s.topography) throw std::invalid_argument("the scene has no topography section");
  return *s.topography;
}
TopographyRecipe& recipe_of(Scene& s) {
  if (!s.topography) throw std::invalid_argument("the scene has no topography section");
  return *s.topography;
}

const char* name_of(SolverMethod m) { return m == SolverMethod::reference ? "reference" : "event"; }

// A number row: FIELD is an lvalue expression of `s`.
#define NUMBER(NAME, UNIT, RANGE, CHECK, WHY, DEFAULT, FIT, FIELD)                                        \
  SceneKey {                                                                                              \
    NAME, KeyKind::number, UNIT, RANGE, [](double x) { return CHECK; }, WHY, DEFAULT, FIT,                \
        [](const Scene& s) { return static_cast<double>(FIELD); }, [](Scene& s, double x) { FIELD = x; }, \
        [](const Scene& s) { return io::format_scene_number(FIELD); }, nullptr, PlausibleRange {}         \
  }
// Any other row: TEXT is a std::string expression of `s`.
#define OTHER(NAME, KIND, TEXT)                                                      \
  SceneKey {                                                                         \
    NAME, KIND, nullptr, nullptr, nullptr, "", kRequired, false, nullptr, nullptr,   \
        [](const Scene& s) { return std::string(TEXT); }, nullptr, PlausibleRange {} \
  }

std::vector<SceneKey> make_table() {
  std::vector<SceneKey> t{
      OTHER("experiment.file", KeyKind::text,
            s.experiment.file.empty() ? std::string()
                                      : std::filesystem::absolute(s.experiment.file).lexically_normal().string()),
      OTHER("experiment.name", KeyKind::text, s.experiment.name),
      OTHER("experiment.description", KeyKind::text, s.experiment.description),
      NUMBER("experiment.mass", "kg", "> 0", x > 0, "", kRequired, true, s.experiment.mass_kg),
      NUMBER("experiment.k_L", "N/m", "> 0", x > 0, "", kRequired, true, s.experiment.k_L),
      NUMBER("experiment.v", "m/s", "> 0", x > 0, "", kRequired, true, s.experiment.v),
      NUMBER("experiment.E", "Pa", "> 0", x > 0, "", kRequired, true, s.experiment.E),
      NUMBER("experiment.nu", nullptr, "in (-1, 0.5]", x > -1 && x <= 0.5, "", kRequired, true, s.experiment.nu),
      NUMBER("experiment.sigma_exp", "Pa", "> 0", x > 0, "", kRequired, true, s.experiment.sigma_exp),
      NUMBER("model.eta", "1/s", ">= 0", x >= 0, "", 100.0, true, s.model.eta),
      NUMBER("model.epsilon", nullptr, "in (0, 1]", x > 0 && x <= 1, "", 0.90, true, s.model.epsilon),
      NUMBER("model.c_min", nullptr, "in (0, 1)", x > 0 && x < 1, "", 0.01, true, s.model.c_min),
      NUMBER("model.p", nullptr, "in [0, 10]", x >= 0 && x <= 10,
             "A0^(p+1) must stay a normal double for areas in [1e-20, 1] m^2", 1.5, true, s.model.p),
      NUMBER("model.alpha_b", "m^(2p+2)/N^2", ">= 0", x >= 0, "", 0.725e-15, true, s.model.alpha_b),
      OTHER("model.junction_shape", KeyKind::choice, name_of(s.model.junction_shape)),
      OTHER("model.area_law", KeyKind::choice, name_of(s.model.area_law)),
      OTHER("model.interactions", KeyKind::choice, name_of(s.model.interactions)),
      NUMBER("model.interaction_cutoff", "m", ">= 0", x >= 0, "0 keeps every pair", 0.0, false,
             s.model.interaction_cutoff),
      OTHER("model.interaction_weighting", KeyKind::choice, name_of(s.model.interaction_weighting)),
      NUMBER("model.position_scale", nullptr, "in (0, 1e6]", x > 0 && x <= 1e6,
             "multiplies every junction centre: an apparent contact s times as wide", 1.0, true,
             s.model.position_scale),
      OTHER("solver.method", KeyKind::choice, name_of(s.solver.method)),
      NUMBER("solver.Ct", nullptr, ">= 1", x >= 1, "reference steps per T0; fewer is unstable for any scene", 1e4,
             false, s.solver.Ct),
      NUMBER("solver.tolerance", nullptr, "in [1e-14, 0.1]", x >= 1e-14 && x <= 0.1,
             "relative error per step; below ~50 machine epsilons the error control only chases rounding and "
             "the steps shrink without bound",
             1e-9, false, s.solver.tolerance),
      NUMBER("solver.interaction_tolerance", nullptr, "in [1e-14, 1e-3]", x >= 1e-14 && x <= 1e-3,
             "fraction of the slip force to which each coupled solve converges; above 1e-3 the peak moves by more than "
             "1e-5 relative",
             1e-8, false, s.solver.interaction_tolerance),
      NUMBER("stop.time", "s", "> 0", x > 0, "", 1.0, false, s.stop.time),
      OTHER("stop.at_first_peak", KeyKind::boolean, s.stop.at_first_peak ? "true" : "false"),
      OTHER("stop.cycles", KeyKind::integer, std::to_string(s.stop.cycles)),
      NUMBER("stop.wall_time", "s", "> 0", x > 0, "seconds of wall-clock time for one run", 3600.0, false,
             s.stop.wall_time),
      NUMBER("stop.max_slips", nullptr, "a whole number in [1, 1e18]", x >= 1 && x <= 1e18 && x == std::floor(x), "",
             0.0, false, s.stop.max_slips),
      NUMBER("output.every", "s", "> 0", x > 0, "", 1e-3, false, s.output.every),
      OTHER("output.series", KeyKind::list,
            [&] {
              std::string y = "[";
              for (std::size_t i = 0; i < s.output.series.size(); ++i) y += (i ? ", " : "") + s.output.series[i];
              return y + "]";
            }()),
      NUMBER("output.peak_min_drop", nullptr, "in (0, 1)", x > 0 && x < 1, "", 0.02, false, s.output.peak_min_drop),
      // A topography scene's recipe (topography_recipe.hpp): setting one re-makes the junctions
      // (one contact solve per distinct surface and load, topography_cache.hpp).
      NUMBER("topography.self_affine.seed", nullptr, "a whole number in [0, 2^53]",
             x >= 0 && x <= 9007199254740992.0 && x == std::floor(x), "larger seeds are not exact as numbers",
             kRequired, false, recipe_of(s).self_affine.seed),
      NUMBER("topography.self_affine.hurst", nullptr, "in (0, 1)", x > 0 && x < 1, "", kRequired, false,
             recipe_of(s).self_affine.hurst),
      NUMBER("topography.self_affine.rms_height_m", "m", "> 0", x > 0, "", kRequired, false,
             recipe_of(s).self_affine.rms_height_m),
      NUMBER("topography.self_affine.rms_slope", nullptr, "> 0", x > 0, "", kRequired, false,
             recipe_of(s).self_affine.rms_slope),
      NUMBER("topography.sphere_radius_m", "m", "> 0", x > 0, "", kRequired, false, recipe_of(s).sphere_radius_m),
      NUMBER("topography.E", "Pa", "> 0", x > 0, "", kRequired, false, recipe_of(s).E_Pa),
      NUMBER("topography.nu", nullptr, "in [0, 0.5]", x >= 0 && x <= 0.5, "", kRequired, false, recipe_of(s).nu),
      NUMBER("topography.load_N", "N", "> 0", x > 0, "", kRequired, false, recipe_of(s).load_N),
  };
  // Plausible ranges: only where a unit slip or a typo gives a value the model accepts and no
  // experiment has. Not alpha_b (its unit changes with p; validate.hpp bounds its effect) nor the
  // solver's, stop's and output's settings (choices of the run, not measurements).
  const std::vector<std::pair<const char*, PlausibleRange>> plausible{
      {"experiment.mass", {1e-3, 10, 0.2, "a slider's"}},
      {"experiment.k_L", {50, 1e7, 9200, "a loading spring's"}},
      {"experiment.v", {1e-8, 0.1, 1e-4, "a driving speed's"}},
      {"experiment.E", {1e5, 1e8, 1.6e6, "an elastomer's"}},
      {"experiment.nu", {0.3, 0.5, 0.5, "an elastomer's"}},
      {"experiment.sigma_exp", {1e4, 1e8, 0.23e6, "an elastomer contact's"}},
      {"model.eta", {0, 1e4, 100, "a damping rate's"}},
      {"model.epsilon", {0.1, 1, 0.9, "a dynamic-to-static friction ratio's"}},
      {"model.interaction_cutoff", {0, 0.1, 1e-3, "a contact's"}},
  };
  for (const auto& [name, range] : plausible)
    for (SceneKey& k : t)
      if (std::string_view(k.name) == name) k.plausible = range;
  for (SceneKey& k : t) {
    const std::string n = k.name;
    // Topography keys: only in a topography scene (its own section, written by the writer).
    if (n.rfind("topography.", 0) == 0) {
      const bool surface = n.rfind("topography.self_affine.", 0) == 0;
      k.written =
          surface ? +[](const Scene& s) { return s.topography && s.topography->kind == TopographyKind::self_affine; }
                  : +[](const Scene& s) { return s.topography.has_value(); };
    }
    // Empty for a scene without topography (the macro's text would throw there).
    if (n == "topography.sphere_radius_m")
      k.text = [](const Scene& s) {
        return s.topography ? io::format_scene_number(s.topography->sphere_radius_m) : std::string();
      };
    if (n == "topography.E")
      k.text = [](const Scene& s) {
        return s.topography ? io::format_scene_number(s.topography->E_Pa) : std::string();
      };
    if (n == "topography.nu")
      k.text = [](const Scene& s) { return s.topography ? io::format_scene_number(s.topography->nu) : std::string(); };
    if (n == "topography.load_N")
      k.text = [](const Scene& s) {
        return s.topography ? io::format_scene_number(s.topography->load_N) : std::string();
      };
    if (n == "topography.self_affine.seed") {
      k.set = [](Scene& s, double x) { recipe_of(s).self_affine.seed = static_cast<std::uint64_t>(x); };
      k.text = [](const Scene& s) {
        return s.topography ? std::to_string(s.topography->self_affine.seed) : std::string();
      };
    }
    if (n == "topography.self_affine.hurst")
      k.text = [](const Scene& s) {
        return s.topography ? io::format_scene_number(s.topography->self_affine.hurst) : std::string();
      };
    // One of rms height and rms slope sets the surface's amplitude: setting one drops the other.
    if (n == "topography.self_affine.rms_height_m") {
      k.set = [](Scene& s, double x) {
        recipe_of(s).self_affine.rms_height_m = x;
        recipe_of(s).self_affine.rms_slope = 0;
      };
      k.text = [](const Scene& s) {
        return s.topography && s.topography->self_affine.rms_height_m > 0
                   ? io::format_scene_number(s.topography->self_affine.rms_height_m)
                   : std::string();
      };
    }
    if (n == "topography.self_affine.rms_slope") {
      k.set = [](Scene& s, double x) {
        recipe_of(s).self_affine.rms_slope = x;
        recipe_of(s).self_affine.rms_height_m = 0;
      };
      k.text = [](const Scene& s) {
        return s.topography && s.topography->self_affine.rms_height_m == 0
                   ? io::format_scene_number(s.topography->self_affine.rms_slope)
                   : std::string();
      };
    }
    // Limits only when set: a default one leaves the text (and so the sweep store's scene hash)
    // as it was before the keys existed.
    // The interaction keys only when interactions are on: a scene of independent junctions has
    // the text (and store hash) it had before they existed.
    if (n == "model.interactions" || n == "model.interaction_cutoff" || n == "model.position_scale")
      k.written = [](const Scene& s) { return s.model.interactions != Interactions::none; };
    // Written only when rigid: interacting scenes of before keep their text and store hash.
    if (n == "model.interaction_weighting")
      k.written = [](const Scene& s) {
        return s.model.interactions != Interactions::none &&
               s.model.interaction_weighting != TractionWeighting::uniform;
      };
    // Only when interactions are on and it differs from the default: scenes of before keep their
    // text and store hash.
    if (n == "solver.interaction_tolerance")
      k.written = [](const Scene& s) {
        return s.model.interactions != Interactions::none &&
               s.solver.interaction_tolerance != SolverSettings{}.interaction_tolerance;
      };
    // A scene given in memory has no experiment file (its junctions are written inline instead).
    if (n == "experiment.file") k.written = [](const Scene& s) { return !s.experiment.file.empty(); };
    if (n == "stop.wall_time") k.written = [](const Scene& s) { return s.stop.wall_time != StopSettings{}.wall_time; };
    if (n == "stop.max_slips") {
      k.set = [](Scene& s, double x) { s.stop.max_slips = static_cast<std::int64_t>(x); };
      k.text = [](const Scene& s) { return std::to_string(s.stop.max_slips); };
      k.written = [](const Scene& s) { return s.stop.max_slips != 0; };
    }
  }
  return t;
}

#undef NUMBER
#undef OTHER

}  // namespace

std::string SceneKey::leaf() const {
  const std::string n = name;
  return n.substr(n.find('.') + 1);
}

std::string SceneKey::section() const {
  const std::string n = name;
  return n.substr(0, n.find('.'));
}

const std::vector<SceneKey>& scene_keys() {
  static const std::vector<SceneKey> table = make_table();
  return table;
}

const SceneKey* find_scene_key(std::string_view dotted) {
  for (const SceneKey& k : scene_keys())
    if (dotted == k.name) return &k;
  return nullptr;
}

const std::vector<std::string>& numeric_scene_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> out;
    for (const SceneKey& k : scene_keys())
      if (k.fittable) out.emplace_back(k.name);
    return out;
  }();
  return keys;
}

const std::vector<std::string>& scene_key_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const SceneKey& k : scene_keys()) out.emplace_back(k.name);
    return out;
  }();
  return names;
}

double scene_value(const Scene& scene, const std::string& key) {
  const SceneKey* k = find_scene_key(key);
  if (!k || !k->fittable) throw std::invalid_argument("not a numeric scene key: " + key);
  return k->get(scene);
}

std::string out_of_range_message(const SceneKey& key, double x) {
  const std::string why = key.why ? key.why : "";
  return "must be " + std::string(key.range) + ", got " + io::format_double(x) + (why.empty() ? "" : " (" + why + ")");
}

std::string implausible_message(const SceneKey& key, double x) {
  const PlausibleRange& p = key.plausible;
  if (!(p.lo < p.hi) || (x >= p.lo && x <= p.hi)) return "";
  using io::format_short;
  const std::string unit = key.unit ? std::string(" ") + key.unit : "";
  std::string m = std::string(key.name) + " = " + io::format_double(x) + unit + " is far " +
                  (x < p.lo ? "below " : "above ") + p.of + " " + format_short(p.lo) + " to " + format_short(p.hi) +
                  unit;
  // The units a value of this SI unit is often written in by mistake, and their factor to SI.
  struct Slip {
    const char* unit;
    const char* in;
    double factor;
  };
  static const Slip slips[] = {{"Pa", "MPa", 1e6},    {"Pa", "kPa", 1e3},   {"Pa", "GPa", 1e9},
                               {"kg", "g", 1e-3},     {"N/m", "N/mm", 1e3}, {"m/s", "mm/s", 1e-3},
                               {"m/s", "um/s", 1e-6}, {"m", "mm", 1e-3},    {"m", "um", 1e-6}};
  const Slip* best = nullptr;
  double best_distance = 0;
  for (const Slip& s : slips) {
    const double si = x * s.factor;
    if (!key.unit || std::string_view(key.unit) != s.unit || !(si >= p.lo && si <= p.hi)) continue;
    const double distance = std::abs(std::log(si / p.typical));
    if (!best || distance < best_distance) best = &s, best_distance = distance;
  }
  if (best) m += std::string("; was it meant in ") + best->in + " (" + format_short(x * best->factor) + unit + ")?";
  return m;
}

std::string scene_value_text(const Scene& scene, const std::string& key) {
  const SceneKey* k = find_scene_key(key);
  if (!k || k->kind == KeyKind::list || (k->written && !k->written(scene))) return "";
  return k->text(scene);
}

}  // namespace asperity
