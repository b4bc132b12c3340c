#include "scene/topography_junctions.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numeric>
#include <stdexcept>

#include "io/digest.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "scene/csv.hpp"
#include "scene/validate.hpp"
#include "surface/height_map_io.hpp"
#include "surface/normal_contact.hpp"
#include "surface/segmentation.hpp"

namespace asperity {

namespace fs = std::filesystem;

namespace {

std::string display_of(const fs::path& p) { return p.lexically_normal().string(); }
std::string num(double x) { return scene_io::format_double(x); }

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

std::string topography_surface_text(const TopographyRecipe& r) {
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

std::string scene_made_by(const TopographyRecipe& r) {
  return "Made by the scene from " + (r.file.empty() ? std::string("its topography section") : r.file.filename().string()) +
         " when it was read.";
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
        throw InputError(r.display, r.topography_line, "topography.self_affine", e.what());
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

TopographyContact solve_topography_contact(const TopographyRecipe& r, int threads) {
  TopographyContact t;
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
    throw InputError(r.display, r.topography_line, "topography", e.what());
  }
  if (!c.converged)
    throw InputError(r.display, 0, r.file.empty() ? "topography.contact.max_iterations" : "contact.max_iterations",
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
    throw InputError(r.display, r.topography_line, "topography",
                     "the contact reaches the edge of the " + std::to_string(n) + " x " + std::to_string(n) +
                         " map: enlarge the map (or lower load_N, or the sphere_radius_m)");
  const auto clusters = contact_clusters(mask, n, map.pixel_m, r.connectivity);
  t.clusters = clusters.size();
  for (const auto& k : clusters) {
    t.junctions.area_m2.push_back(k.area_m2);
    t.junctions.x_m.push_back(k.x_m);
    t.junctions.y_m.push_back(k.y_m);
  }
  t.merges = merge_overlapping_junctions(t.junctions);
  // The junctions must pass what a junctions file's rows pass (what generate writes is read back
  // as one): a pixel of 1e-11 m or a map of 1e5 m pixels makes areas no command accepts.
  const JunctionPopulation& J = t.junctions;
  for (std::size_t i = 0; i < J.size(); ++i) {
    std::string why = scene_io::junction_area_problem(J.area_m2[i]);
    for (const double v : {J.x_m[i], J.y_m[i]})
      if (why.empty()) why = scene_io::junction_coordinate_problem(v);
    if (!why.empty())
      throw InputError(r.display, r.topography_line, "topography",
                       "junction " + std::to_string(i + 1) + " of the " + std::to_string(J.size()) +
                           " this surface makes: " + why + " (the map's pixel size, load_N and sphere_radius_m " +
                           "set the junctions' sizes)");
  }
  return t;
}

Experiment topography_experiment(const TopographyRecipe& r, const TopographyContact& t, const std::string& made_by) {
  Experiment e;
  e.name = r.name;
  e.mass_kg = r.mass_kg > 0 ? r.mass_kg : r.load_N / r.gravity;
  e.k_L = r.k_L;
  e.v = r.v;
  e.E = r.E_Pa;
  e.nu = r.nu;
  e.sigma_exp = r.sigma_exp;
  e.junctions = t.junctions;
  e.description = "Junctions from topography: the contact clusters of a sphere of R = " + num(r.sphere_radius_m) +
                  " m on a rigid flat at P = " + num(r.load_N) + " N, merged where their equivalent discs overlap (" +
                  std::to_string(t.clusters) + " clusters, " + std::to_string(e.junctions.size()) +
                  " junctions); surface " + topography_surface_text(r) + ". " + made_by;
  return e;
}

}  // namespace asperity
