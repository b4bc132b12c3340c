#include "scene/topography_recipe_load.hpp"

#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "surface/height_map_io.hpp"

namespace asperity {

namespace fs = std::filesystem;
using io::MapView;
using io::Source;

namespace {

double positive(const MapView& m, const std::string& k, const char* unit) {
  const YAML::Node n = m.require(k);
  const double x = m.number(n, k, unit);
  if (!(x > 0.0)) m.fail_at(n, k, "must be > 0, got " + io::format_double(x));
  return x;
}

void get_positive(const MapView& m, const std::string& k, double& out, const char* unit) {
  if (m.find(k)) out = positive(m, k, unit);
}

// n pixels per side in [lo, kMaxHeightMapSide] (even when asked): checked before any allocation.
std::size_t side(const MapView& m, bool even) {
  const YAML::Node n = m.require("n");
  const int v = m.integer(n, "n");
  const int lo = even ? 4 : 2;
  if (v < lo || static_cast<std::size_t>(v) > kMaxHeightMapSide || (even && v % 2))
    m.fail_at(n, "n",
              std::string("must be ") + (even ? "an even number " : "") + "in [" + std::to_string(lo) + ", " +
                  std::to_string(kMaxHeightMapSide) + "], got " + std::to_string(v));
  return static_cast<std::size_t>(v);
}

// A pixel size within what a contact solve accepts (surface/height_map_io.hpp), at key `k`.
double pixel_checked(const MapView& m, const std::string& k, double pixel_m, const std::string& what = "") {
  if (const std::string why = pixel_size_problem(pixel_m); !why.empty()) m.fail_at(*m.find(k), k, what + why);
  return pixel_m;
}

// The pixel size, from pixel_m or size_m (the side of the map), exactly one of them.
double pixel_of(const MapView& m, std::size_t n) {
  const auto p = m.find("pixel_m"), s = m.find("size_m");
  if (p.has_value() == s.has_value()) m.fail_at(p ? *p : m.node(), "pixel_m", "give exactly one of pixel_m and size_m");
  if (p) return pixel_checked(m, "pixel_m", positive(m, "pixel_m", "m"));
  const double size = positive(m, "size_m", "m");
  return pixel_checked(m, "size_m", size / static_cast<double>(n),
                       "gives pixels of " + io::format_double(size / static_cast<double>(n)) + " m (size_m / n): ");
}

const std::vector<std::string> kSurfaceKeys{"smooth", "self_affine", "file", "pixel_m"};
const std::vector<std::string> kRecipeKeys{"name", "sphere_radius_m", "E", "nu", "load_N", "contact", "slider"};

// The surface keys of `t` (a recipe's topography section, or a scene's lifted one).
void read_surface(const MapView& t, const YAML::Node& tn, const fs::path& base_dir, TopographyRecipe& r) {
  const Source& src = t.source();
  r.topography_line = tn.Mark().is_null() ? 0 : tn.Mark().line + 1;
  const auto sm = t.find("smooth"), sa = t.find("self_affine"), fi = t.find("file");
  if (int(sm.has_value()) + int(sa.has_value()) + int(fi.has_value()) != 1)
    t.fail_at(tn, "file", "give exactly one of smooth, self_affine and file");
  if (!fi && t.find("pixel_m")) t.fail_at(*t.find("pixel_m"), "pixel_m", "only for a CSV height map (file: ...csv)");
  if (sm) {
    r.kind = TopographyKind::smooth;
    const MapView m(src, *sm, t.key("smooth"), {"n", "pixel_m", "size_m"});
    r.n = side(m, false);
    r.pixel_m = pixel_of(m, r.n);
  } else if (sa) {
    r.kind = TopographyKind::self_affine;
    const MapView m(src, *sa, t.key("self_affine"),
                    {"seed", "n", "pixel_m", "size_m", "hurst", "rolloff_wavelength_m", "short_wavelength_m",
                     "rms_height_m", "rms_slope"});
    SelfAffineSpec& s = r.self_affine;
    s.seed = m.seed(m.require("seed"), "seed");
    r.n = s.n = side(m, true);
    r.pixel_m = pixel_of(m, r.n);
    s.length_m = r.pixel_m * static_cast<double>(r.n);
    const YAML::Node hn = m.require("hurst");
    s.hurst = m.number(hn, "hurst", nullptr);
    if (!(s.hurst > 0 && s.hurst < 1)) m.fail_at(hn, "hurst", "must be in (0, 1), got " + io::format_double(s.hurst));
    get_positive(m, "rolloff_wavelength_m", s.rolloff_wavelength_m, "m");
    get_positive(m, "short_wavelength_m", s.short_wavelength_m, "m");
    const auto hr = m.find("rms_height_m"), sl = m.find("rms_slope");
    if (hr.has_value() == sl.has_value())
      m.fail_at(hr ? *hr : *sa, "rms_height_m", "give exactly one of rms_height_m and rms_slope");
    if (hr) s.rms_height_m = positive(m, "rms_height_m", "m");
    if (sl) s.rms_slope = positive(m, "rms_slope", nullptr);
    if (const auto p = topography_recipe_problem(r)) {
      const std::string leaf = p->key.substr(p->key.rfind('.') + 1);
      m.fail_at(*m.find(leaf), leaf, p->message);
    }
  } else {
    r.kind = TopographyKind::measured;
    const std::string rel = t.string(*fi, "file");
    if (io::trim(rel).empty()) t.fail_at(*fi, "file", "empty path (expected a height map)");
    r.map_file = base_dir / fs::path(rel);
    const std::string ext = r.map_file.extension().string();
    const bool csv = ext == ".csv", header = ext == ".yaml" || ext == ".yml";
    if (!csv && !header)
      t.fail_at(*fi, "file",
                "expected a .csv matrix of heights or a .yaml header of a float64 file, got " + io::quote(rel));
    const std::string why = io::input_file_problem(r.map_file, csv ? io::kMaxCsvBytes : io::kMaxYamlBytes);
    if (why == "file not found")
      t.fail_at(*fi, "file",
                "height map not found: " + io::quote(rel) + " (looked for " + io::input_path(r.map_file) + ")");
    if (!why.empty()) t.fail_at(*fi, "file", "height map " + why + ": " + io::input_path(r.map_file));
    if (csv)
      r.pixel_m = pixel_checked(t, "pixel_m", positive(t, "pixel_m", "m"));
    else if (const auto p = t.find("pixel_m"))
      t.fail_at(*p, "pixel_m", "a binary height map gives its pixel size in its header");
  }
}

// Everything but the surface: name, sphere, elastomer, load, contact and slider, from `top`.
void read_rest(const MapView& top, TopographyRecipe& r) {
  const Source& src = top.source();
  if (const auto n = top.find("name")) {
    r.name = top.string(*n, "name");
    if (r.name.empty() || io::has_control_char(r.name)) top.fail_at(*n, "name", "must be a non-empty single-line name");
  }
  // Ranges: topography_number_problem (topography_recipe.hpp), shared with the Python bindings.
  const auto in_range = [](const MapView& m, const YAML::Node& n, const std::string& key, const std::string& checked,
                           double x) {
    if (const std::string why = topography_number_problem(checked, x); !why.empty()) m.fail_at(n, key, why);
    return x;
  };
  const auto number = [&](const char* key, const char* unit) {
    const YAML::Node n = top.require(key);
    return in_range(top, n, key, key, top.number(n, key, unit));
  };
  r.sphere_radius_m = number("sphere_radius_m", "m");
  r.E_Pa = number("E", "Pa");
  r.nu = number("nu", nullptr);
  r.load_N = number("load_N", "N");
  if (const auto cn = top.find("contact")) {
    const MapView m(src, *cn, top.key("contact"), {"tolerance", "max_iterations", "connectivity"});
    if (const auto n = m.find("tolerance"))
      r.tolerance = in_range(m, *n, "tolerance", "contact.tolerance", m.number(*n, "tolerance", nullptr));
    if (const auto n = m.find("max_iterations"))
      r.max_iterations = static_cast<int>(
          in_range(m, *n, "max_iterations", "contact.max_iterations", m.integer(*n, "max_iterations")));
    if (const auto n = m.find("connectivity")) {
      const double c = in_range(m, *n, "connectivity", "contact.connectivity", m.integer(*n, "connectivity"));
      r.connectivity = c == 4 ? Connectivity::four : Connectivity::eight;
    }
  }
  if (const auto sn = top.find("slider")) {
    const MapView m(src, *sn, top.key("slider"), {"gravity", "mass_kg", "k_L", "v", "sigma_exp"});
    get_positive(m, "gravity", r.gravity, "m/s^2");
    get_positive(m, "mass_kg", r.mass_kg, "kg");
    get_positive(m, "k_L", r.k_L, "N/m");
    get_positive(m, "v", r.v, "m/s");
    get_positive(m, "sigma_exp", r.sigma_exp, "Pa");
  }
}

// A recipe file's tree with its topography section lifted (the scene form), marks stripped:
// values that came from the file are not at the scene's lines.
YAML::Node lifted_file_tree(const YAML::Node& root) {
  YAML::Node out(YAML::NodeType::Map);
  for (auto it = root.begin(); it != root.end(); ++it) {
    const std::string k = it->first.Scalar();
    if (k != "topography")
      out[k] = io::strip_marks(it->second);
    else
      for (auto jt = it->second.begin(); jt != it->second.end(); ++jt)
        out[jt->first.Scalar()] = io::strip_marks(jt->second);
  }
  return out;
}

// `over`'s entries replace `base`'s, maps merged key by key. One of a pair of alternatives
// (rms_height_m / rms_slope, pixel_m / size_m) replaces the other.
YAML::Node merged(const YAML::Node& base, const YAML::Node& over) {
  if (!base.IsMap() || !over.IsMap()) return over;
  static const std::vector<std::pair<std::string, std::string>> kAlternatives{{"rms_height_m", "rms_slope"},
                                                                              {"pixel_m", "size_m"}};
  YAML::Node out(YAML::NodeType::Map);
  for (auto it = base.begin(); it != base.end(); ++it) {
    const std::string k = it->first.Scalar();
    bool dropped = false;
    for (const auto& [a, b] : kAlternatives)
      dropped = dropped || (k == a && over[b].IsDefined()) || (k == b && over[a].IsDefined());
    if (dropped) continue;
    out[k] = over[k].IsDefined() ? merged(it->second, over[k]) : it->second;
  }
  for (auto it = over.begin(); it != over.end(); ++it)
    if (!out[it->first.Scalar()].IsDefined()) out[it->first] = it->second;
  return out;
}

}  // namespace

bool is_topography_recipe(const fs::path& path) {
  const YAML::Node root = io::load_yaml_file(path, io::input_path(path));
  if (!root.IsMap()) return false;
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == "topography") return true;
  return false;
}

TopographyRecipe load_topography_recipe(const fs::path& path) {
  const std::string display = io::input_path(path);
  const YAML::Node root = io::load_yaml_file(path, display);
  const Source src{display, nullptr};
  TopographyRecipe r;
  r.file = path;
  r.display = display;
  std::vector<std::string> keys = kRecipeKeys;
  keys.push_back("topography");
  const MapView top(src, root, "", keys, 1);
  const YAML::Node tn = top.require("topography");
  read_surface(MapView(src, tn, "topography", kSurfaceKeys), tn, path.parent_path(), r);
  read_rest(top, r);
  return r;
}

TopographyRecipe topography_recipe_from_scene(const Source& src, const YAML::Node& section, const fs::path& base_dir) {
  std::vector<std::string> keys = kRecipeKeys;
  keys.insert(keys.end(), kSurfaceKeys.begin(), kSurfaceKeys.end());
  keys.push_back("recipe");
  const MapView top(src, section, "topography", keys);
  TopographyRecipe r;
  YAML::Node tree = section;
  fs::path map_dir = base_dir;
  if (const auto rn = top.find("recipe")) {
    // The file alone first, so that its own errors name it and its lines; then the scene's values over it.
    const std::string rel = top.string(*rn, "recipe");
    if (io::trim(rel).empty()) top.fail_at(*rn, "recipe", "empty path (expected a topography recipe)");
    const fs::path p = base_dir / fs::path(rel);
    if (const std::string why = io::input_file_problem(p, io::kMaxYamlBytes); !why.empty())
      top.fail_at(*rn, "recipe", "topography recipe " + why + ": " + io::input_path(p));
    r = load_topography_recipe(p);
    YAML::Node over(YAML::NodeType::Map);
    for (auto it = section.begin(); it != section.end(); ++it)
      if (it->first.Scalar() != "recipe") over[it->first] = it->second;
    tree = merged(lifted_file_tree(io::load_yaml_file(p, io::input_path(p))), over);
    map_dir = p.parent_path();  // a height map named in the file is relative to it
    const fs::path file = r.file;
    r = TopographyRecipe{};
    r.file = file;
  }
  const MapView lifted(src, tree, "topography", keys);
  read_surface(lifted, tree, map_dir, r);
  read_rest(lifted, r);
  r.display = src.file;
  return r;
}

}  // namespace asperity
