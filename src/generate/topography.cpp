#include "generate/topography.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/digest.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/load.hpp"
#include "scene/validate.hpp"
#include "surface/height_map_io.hpp"

namespace asperity {

namespace fs = std::filesystem;
using scene_io::MapView;
using scene_io::Source;

namespace {

std::string display_of(const fs::path& p) { return p.lexically_normal().string(); }
std::string num(double x) { return scene_io::format_double(x); }

double positive(const MapView& m, const std::string& k, const char* unit) {
  const YAML::Node n = m.require(k);
  const double x = m.number(n, k, unit);
  if (!(x > 0.0)) m.fail_at(n, k, "must be > 0, got " + num(x));
  return x;
}

void get_positive(const MapView& m, const std::string& k, double& out, const char* unit) {
  if (m.find(k)) out = positive(m, k, unit);
}

std::uint64_t seed_value(const MapView& m, const std::string& k) { return m.seed(m.require(k), k); }

// n pixels per side in [lo, kMaxHeightMapSide] (even when asked): checked before any allocation.
std::size_t side(const MapView& m, bool even) {
  const YAML::Node n = m.require("n");
  const int v = m.integer(n, "n");
  const int lo = even ? 4 : 2;
  if (v < lo || static_cast<std::size_t>(v) > kMaxHeightMapSide || (even && v % 2))
    m.fail_at(n, "n", std::string("must be ") + (even ? "an even number " : "") + "in [" + std::to_string(lo) + ", " +
                          std::to_string(kMaxHeightMapSide) + "], got " + std::to_string(v));
  return static_cast<std::size_t>(v);
}

// The pixel size, from pixel_m or size_m (the side of the map), exactly one of them.
double pixel_of(const MapView& m, std::size_t n) {
  const auto p = m.find("pixel_m"), s = m.find("size_m");
  if (p.has_value() == s.has_value())
    m.fail_at(p ? *p : m.node(), "pixel_m", "give exactly one of pixel_m and size_m");
  return p ? positive(m, "pixel_m", "m") : positive(m, "size_m", "m") / static_cast<double>(n);
}

// One line of the provenance header per call: "# " + text.
void comment(std::string& s, const std::string& text) { s += "# " + text + "\n"; }

std::string kind_text(const TopographyRecipe& r) {
  switch (r.kind) {
    case TopographyKind::smooth:
      return "a smooth sphere (no roughness), generated from a synthetic surface";
    case TopographyKind::self_affine: {
      const SelfAffineSpec& a = r.self_affine;
      return "generated from a synthetic surface: self-affine (Fourier filtering, surface/self_affine.hpp), seed " +
             std::to_string(a.seed) + ", hurst " + num(a.hurst) + ", rolloff_wavelength_m " +
             (a.rolloff_wavelength_m > 0 ? num(a.rolloff_wavelength_m) : "none (= size)") + ", short_wavelength_m " +
             (a.short_wavelength_m > 0 ? num(a.short_wavelength_m) : "2 pixels") +
             (a.rms_height_m > 0 ? ", rms_height_m " + num(a.rms_height_m) : ", rms_slope " + num(a.rms_slope));
    }
    case TopographyKind::measured:
      return "measured height map " + r.map_file.filename().string();
  }
  return "";
}

std::string heights_sha256(const HeightMap& m) {
  Sha256 h;
  std::string bytes(8, '\0');
  for (const double x : m.h_m) {
    const auto u = std::bit_cast<std::uint64_t>(x);
    for (std::size_t b = 0; b < 8; ++b) bytes[b] = static_cast<char>((u >> (8 * b)) & 0xff);
    h.update(bytes);
  }
  return h.hex();
}

}  // namespace

bool is_topography_recipe(const fs::path& path) {
  const YAML::Node root = scene_io::load_yaml_file(path, display_of(path));
  if (!root.IsMap()) return false;
  for (auto it = root.begin(); it != root.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == "topography") return true;
  return false;
}

TopographyRecipe load_topography_recipe(const fs::path& path) {
  const std::string display = display_of(path);
  const YAML::Node root = scene_io::load_yaml_file(path, display);
  const Source src{display, nullptr};
  TopographyRecipe r;
  r.file = path;
  const MapView top(src, root, "",
                    {"name", "topography", "sphere_radius_m", "E", "nu", "load_N", "contact", "slider"}, 1);
  if (const auto n = top.find("name")) {
    r.name = top.string(*n, "name");
    if (r.name.empty() || scene_io::has_control_char(r.name)) top.fail_at(*n, "name", "must be a non-empty single-line name");
  }

  {
    const YAML::Node tn = top.require("topography");
    r.topography_line = tn.Mark().is_null() ? 0 : tn.Mark().line + 1;
    const MapView t(src, tn, "topography", {"smooth", "self_affine", "file", "pixel_m"});
    const auto sm = t.find("smooth"), sa = t.find("self_affine"), fi = t.find("file");
    if (int(sm.has_value()) + int(sa.has_value()) + int(fi.has_value()) != 1)
      t.fail_at(tn, "file", "give exactly one of smooth, self_affine and file");
    if (!fi && t.find("pixel_m"))
      t.fail_at(*t.find("pixel_m"), "pixel_m", "only for a CSV height map (file: ...csv)");
    if (sm) {
      r.kind = TopographyKind::smooth;
      const MapView m(src, *sm, "topography.smooth", {"n", "pixel_m", "size_m"});
      r.n = side(m, false);
      r.pixel_m = pixel_of(m, r.n);
    } else if (sa) {
      r.kind = TopographyKind::self_affine;
      const MapView m(src, *sa, "topography.self_affine",
                      {"seed", "n", "pixel_m", "size_m", "hurst", "rolloff_wavelength_m", "short_wavelength_m",
                       "rms_height_m", "rms_slope"});
      SelfAffineSpec& s = r.self_affine;
      s.seed = seed_value(m, "seed");
      r.n = s.n = side(m, true);
      r.pixel_m = pixel_of(m, r.n);
      s.length_m = r.pixel_m * static_cast<double>(r.n);
      const YAML::Node hn = m.require("hurst");
      s.hurst = m.number(hn, "hurst", nullptr);
      if (!(s.hurst > 0 && s.hurst < 1)) m.fail_at(hn, "hurst", "must be in (0, 1), got " + num(s.hurst));
      get_positive(m, "rolloff_wavelength_m", s.rolloff_wavelength_m, "m");
      get_positive(m, "short_wavelength_m", s.short_wavelength_m, "m");
      const double lr = s.rolloff_wavelength_m > 0 ? s.rolloff_wavelength_m : s.length_m;
      const double ls = s.short_wavelength_m > 0 ? s.short_wavelength_m : 2 * r.pixel_m;
      if (const auto n = m.find("rolloff_wavelength_m"); n && lr > s.length_m * (1 + 1e-12))
        m.fail_at(*n, "rolloff_wavelength_m", "must be at most the map's size " + num(s.length_m) + " m");
      if (const auto n = m.find("short_wavelength_m"); n && (ls < 2 * r.pixel_m * (1 - 1e-12) || !(ls < lr)))
        m.fail_at(*n, "short_wavelength_m",
                  "must be at least 2 pixels (" + num(2 * r.pixel_m) + " m) and below the roll-off wavelength " +
                      num(lr) + " m");
      const auto hr = m.find("rms_height_m"), sl = m.find("rms_slope");
      if (hr.has_value() == sl.has_value())
        m.fail_at(hr ? *hr : *sa, "rms_height_m", "give exactly one of rms_height_m and rms_slope");
      if (hr) s.rms_height_m = positive(m, "rms_height_m", "m");
      if (sl) s.rms_slope = positive(m, "rms_slope", nullptr);
    } else {
      r.kind = TopographyKind::measured;
      const std::string rel = t.string(*fi, "file");
      if (scene_io::trim(rel).empty()) t.fail_at(*fi, "file", "empty path (expected a height map)");
      r.map_file = path.parent_path() / fs::path(rel);
      const std::string ext = r.map_file.extension().string();
      const bool csv = ext == ".csv", header = ext == ".yaml" || ext == ".yml";
      if (!csv && !header)
        t.fail_at(*fi, "file", "expected a .csv matrix of heights or a .yaml header of a float64 file, got " +
                                   scene_io::quote(rel));
      const std::string why =
          scene_io::input_file_problem(r.map_file, csv ? scene_io::kMaxCsvBytes : scene_io::kMaxYamlBytes);
      if (why == "file not found")
        t.fail_at(*fi, "file", "height map not found: " + scene_io::quote(rel) + " (looked for " +
                                   display_of(r.map_file) + ")");
      if (!why.empty()) t.fail_at(*fi, "file", "height map " + why + ": " + display_of(r.map_file));
      if (csv) r.pixel_m = positive(t, "pixel_m", "m");
      else if (const auto p = t.find("pixel_m"))
        t.fail_at(*p, "pixel_m", "a binary height map gives its pixel size in its header");
    }
  }

  r.sphere_radius_m = positive(top, "sphere_radius_m", "m");
  r.E_Pa = positive(top, "E", "Pa");
  {
    const YAML::Node n = top.require("nu");
    r.nu = top.number(n, "nu", nullptr);
    if (!(r.nu >= 0.0 && r.nu <= 0.5)) top.fail_at(n, "nu", "must be in [0, 0.5], got " + num(r.nu));
  }
  r.load_N = positive(top, "load_N", "N");

  if (const auto cn = top.find("contact")) {
    const MapView m(src, *cn, "contact", {"tolerance", "max_iterations", "connectivity"});
    if (const auto n = m.find("tolerance")) {
      r.tolerance = m.number(*n, "tolerance", nullptr);
      if (!(r.tolerance >= 1e-15 && r.tolerance < 1)) m.fail_at(*n, "tolerance", "must be in [1e-15, 1)");
    }
    if (const auto n = m.find("max_iterations")) {
      r.max_iterations = m.integer(*n, "max_iterations");
      if (r.max_iterations < 1 || r.max_iterations > 1'000'000)
        m.fail_at(*n, "max_iterations", "must be in [1, 1000000], got " + std::to_string(r.max_iterations));
    }
    if (const auto n = m.find("connectivity")) {
      const int c = m.integer(*n, "connectivity");
      if (c != 4 && c != 8) m.fail_at(*n, "connectivity", "must be 4 or 8, got " + std::to_string(c));
      r.connectivity = c == 4 ? Connectivity::four : Connectivity::eight;
    }
  }
  if (const auto sn = top.find("slider")) {
    const MapView m(src, *sn, "slider", {"gravity", "mass_kg", "k_L", "v", "sigma_exp"});
    get_positive(m, "gravity", r.gravity, "m/s^2");
    get_positive(m, "mass_kg", r.mass_kg, "kg");
    get_positive(m, "k_L", r.k_L, "N/m");
    get_positive(m, "v", r.v, "m/s");
    get_positive(m, "sigma_exp", r.sigma_exp, "Pa");
  }
  return r;
}

HeightMap topography_surface(const TopographyRecipe& r) {
  switch (r.kind) {
    case TopographyKind::smooth: {
      HeightMap m;
      m.n = r.n;
      m.pixel_m = r.pixel_m;
      m.h_m.assign(r.n * r.n, 0.0);
      return m;
    }
    case TopographyKind::self_affine:
      try {
        return self_affine_surface(r.self_affine);
      } catch (const std::invalid_argument& e) {  // a combination the key checks let through
        throw InputError(display_of(r.file), r.topography_line, "topography.self_affine", e.what());
      }
    case TopographyKind::measured:
      if (r.map_file.extension() == ".csv") return read_height_map_csv(r.map_file, display_of(r.map_file), r.pixel_m);
      return read_height_map_binary(r.map_file, display_of(r.map_file));
  }
  throw std::logic_error("topography_surface: unknown kind");
}

std::size_t merge_overlapping_junctions(JunctionPopulation& J) {
  if (J.x_m.size() != J.size() || J.y_m.size() != J.size())
    throw std::invalid_argument("merge_overlapping_junctions: junctions need positions");
  std::size_t merges = 0;
  // Each pass is O(N) (first_overlap's cell grid) and removes one junction: O(N²) at worst, in
  // practice a few merges per cluster of touching spots.
  while (const auto pair = first_overlap(J)) {
    const auto [i, j] = *pair;
    const double A = J.area_m2[i] + J.area_m2[j];
    J.x_m[i] = (J.area_m2[i] * J.x_m[i] + J.area_m2[j] * J.x_m[j]) / A;
    J.y_m[i] = (J.area_m2[i] * J.y_m[i] + J.area_m2[j] * J.y_m[j]) / A;
    J.area_m2[i] = A;
    const auto at = static_cast<std::ptrdiff_t>(j);
    J.area_m2.erase(J.area_m2.begin() + at);
    J.x_m.erase(J.x_m.begin() + at);
    J.y_m.erase(J.y_m.begin() + at);
    ++merges;
  }
  std::vector<std::size_t> order(J.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (J.area_m2[a] != J.area_m2[b]) return J.area_m2[a] > J.area_m2[b];
    return J.x_m[a] != J.x_m[b] ? J.x_m[a] < J.x_m[b] : J.y_m[a] < J.y_m[b];
  });
  JunctionPopulation sorted;
  for (const std::size_t k : order) {
    sorted.area_m2.push_back(J.area_m2[k]);
    sorted.x_m.push_back(J.x_m[k]);
    sorted.y_m.push_back(J.y_m[k]);
  }
  J = std::move(sorted);
  return merges;
}

TopographyJunctions build_topography_junctions(const TopographyRecipe& r, int threads) {
  const std::string display = display_of(r.file);
  TopographyJunctions t;
  t.recipe_sha256 = sha256_hex(scene_io::read_input_file(r.file, display, scene_io::kMaxYamlBytes));

  HeightMap map = topography_surface(r);
  t.n = map.n;
  t.pixel_m = map.pixel_m;
  t.heights_sha256 = heights_sha256(map);
  t.rms_height_m = rms_height(map);
  t.rms_slope = rms_slope(map);
  add_sphere(map, r.sphere_radius_m);

  NormalContactSettings s;
  s.E_star_Pa = r.E_Pa / (1 - r.nu * r.nu);
  s.periodic = false;  // a sphere: an isolated contact
  s.load_N = r.load_N;
  s.tolerance = r.tolerance;
  s.max_iterations = r.max_iterations;
  s.threads = threads;
  NormalContact c;
  try {
    c = solve_normal_contact(map, s);
  } catch (const std::invalid_argument& e) {
    throw InputError(display, r.topography_line, "topography", e.what());
  }
  if (!c.converged)
    throw InputError(display, 0, "contact.max_iterations",
                     "the normal contact did not converge in " + std::to_string(c.iterations) +
                         " iterations (residual " + scene_io::format_short(c.residual) + " > tolerance " +
                         num(r.tolerance) + "); raise contact.max_iterations or contact.tolerance");
  t.iterations = c.iterations;
  t.residual = c.residual;
  t.contact_area_m2 = c.area_m2;

  const std::size_t n = map.n;
  std::vector<unsigned char> mask(n * n, 0);
  bool edge = false;
  for (std::size_t k = 0; k < n * n; ++k) {
    mask[k] = c.pressure_Pa[k] > 0;
    const std::size_t i = k / n, j = k % n;
    edge = edge || (mask[k] && (i == 0 || j == 0 || i + 1 == n || j + 1 == n));
  }
  // A contact cut by the map's edge would be a smaller, wrong one (the solve is not periodic).
  if (edge)
    throw InputError(display, r.topography_line, "topography",
                     "the contact reaches the edge of the " + std::to_string(n) + " x " + std::to_string(n) +
                         " map: enlarge the map (or lower load_N, or the sphere_radius_m)");
  const auto clusters = contact_clusters(mask, n, map.pixel_m, r.connectivity);
  t.clusters = clusters.size();

  Experiment& e = t.experiment;
  e.name = r.name;
  e.mass_kg = r.mass_kg > 0 ? r.mass_kg : r.load_N / r.gravity;
  e.k_L = r.k_L;
  e.v = r.v;
  e.E = r.E_Pa;
  e.nu = r.nu;
  e.sigma_exp = r.sigma_exp;
  for (const auto& k : clusters) {
    e.junctions.area_m2.push_back(k.area_m2);
    e.junctions.x_m.push_back(k.x_m);
    e.junctions.y_m.push_back(k.y_m);
  }
  t.merges = merge_overlapping_junctions(e.junctions);
  e.description = "Junctions from topography: the contact clusters of a sphere of R = " + num(r.sphere_radius_m) +
                  " m on a rigid flat at P = " + num(r.load_N) + " N, merged where their equivalent discs overlap (" +
                  std::to_string(t.clusters) + " clusters, " + std::to_string(e.junctions.size()) +
                  " junctions); surface " + kind_text(r) + ". Written by `asperity generate` from " +
                  r.file.filename().string() + "; provenance in the header of junctions.csv.";
  return t;
}

std::string topography_junctions_csv(const TopographyRecipe& r, const TopographyJunctions& t) {
  const JunctionPopulation& J = t.experiment.junctions;
  double total = 0;
  for (const double A : J.area_m2) total += A;
  const std::size_t n = t.n;
  std::string s;
  comment(s, "Junctions from topography: written by `asperity generate` from " + r.file.filename().string() +
                 "; regenerate rather than edit.");
  comment(s, "recipe_sha256: " + t.recipe_sha256);
  comment(s, "surface: " + kind_text(r));
  comment(s, std::string("seed: ") +
                 (r.kind == TopographyKind::self_affine ? std::to_string(r.self_affine.seed) : "none"));
  comment(s, "n: " + std::to_string(n) + ", pixel_m: " + num(t.pixel_m) + ", size_m: " +
                 num(t.pixel_m * static_cast<double>(n)));
  comment(s, "rms_height_m: " + num(t.rms_height_m) + ", rms_slope: " + num(t.rms_slope) +
                 " (before the sphere; heights sha256 " + t.heights_sha256 + ", float64 LE row-major)");
  comment(s, "sphere_radius_m: " + num(r.sphere_radius_m) + ", E: " + num(r.E_Pa) + " Pa, nu: " + num(r.nu) +
                 ", rigid counter-surface");
  comment(s, "load_N: " + num(r.load_N) + ", solver iterations: " + std::to_string(t.iterations) +
                 ", residual: " + num(t.residual) + " (tolerance " + num(r.tolerance) + ")");
  comment(s, "clusters: " + std::to_string(t.clusters) + " (connectivity " +
                 (r.connectivity == Connectivity::four ? "4" : "8") + "), merges of overlapping equivalent discs: " +
                 std::to_string(t.merges));
  comment(s, "junctions: " + std::to_string(J.size()) + ", total area_m2: " + num(total));
  s += "area_m2,x_m,y_m\n";
  for (std::size_t i = 0; i < J.size(); ++i)
    s += csv_number(J.area_m2[i]) + ',' + csv_number(J.x_m[i]) + ',' + csv_number(J.y_m[i]) + '\n';
  return s;
}

void write_topography_experiment(const TopographyRecipe& r, const TopographyJunctions& t, const fs::path& out_dir) {
  fs::create_directories(out_dir);
  write_file_atomically(out_dir / "junctions.csv", topography_junctions_csv(r, t), Durability::unsynced);
  write_file_atomically(out_dir / "experiment.yaml", experiment_to_yaml(t.experiment, "junctions.csv", ""),
                        Durability::unsynced);
}

}  // namespace asperity
