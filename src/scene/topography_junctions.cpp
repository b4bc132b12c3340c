#include "scene/topography_junctions.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "io/digest.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "physics/contact_law.hpp"  // disc_radius
#include "scene/csv.hpp"
#include "scene/validate.hpp"
#include "surface/height_map_io.hpp"
#include "surface/neighbour_grid.hpp"
#include "surface/normal_contact.hpp"
#include "surface/segmentation.hpp"

namespace asperity {

namespace fs = std::filesystem;

namespace {

std::string display_of(const fs::path& p) { return p.lexically_normal().string(); }
std::string num(double x) { return io::format_double(x); }

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
  return "Made by the scene from " +
         (r.file.empty() ? std::string("its topography section") : r.file.filename().string()) + " when it was read.";
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

std::size_t merge_overlapping_junctions(JunctionPopulation& J, std::uint64_t max_work) {
  if (J.x_m.size() != J.size() || J.y_m.size() != J.size())
    throw std::invalid_argument("merge_overlapping_junctions: junctions need positions");
  const std::size_t n = J.size();
  std::size_t merges = 0;
  std::vector<unsigned char> alive(n, 1);
  if (n >= 2) {
    // The pair merged next is the one a full scan would find first (scene/validate.cpp
    // first_overlap: the lowest index with an overlapping disc of a higher index, and of those
    // discs the first in its grid's cell order), so the result is that of merging one pair per
    // scan; only the discs a merge changed are looked at again. A junction keeps its index (the
    // lower of a pair lives on, as the erase of the other kept it), so index order is the scan's.
    std::vector<double> r(n);
    for (std::size_t k = 0; k < n; ++k) r[k] = disc_radius(J.area_m2[k]);
    const auto reach_of = [&](std::size_t k) { return std::max(std::abs(J.x_m[k]), std::abs(J.y_m[k])); };
    std::multiset<double> reach;  // of the living discs: the scan's grid extent
    for (std::size_t k = 0; k < n; ++k) reach.insert(reach_of(k));
    double r_max = *std::max_element(r.begin(), r.end());
    // Discs of up to half a cell (twice the median radius) in a grid, searched in the cells
    // their radius reaches; the few larger ones (a merge grows them) apart, checked one by one.
    std::vector<double> by_size = r;
    std::nth_element(by_size.begin(), by_size.begin() + static_cast<std::ptrdiff_t>(n / 2), by_size.end());
    NeighbourGrid grid(2 * by_size[n / 2], *reach.rbegin());
    const double h = grid.cell();
    std::vector<std::size_t> big;
    const auto place = [&](std::size_t k) {
      if (2 * r[k] > h)
        big.push_back(k);
      else
        grid.insert(k, J.x_m[k], J.y_m[k]);
    };
    const auto unplace = [&](std::size_t k) {
      if (2 * r[k] > h)
        big.erase(std::find(big.begin(), big.end(), k));
      else
        grid.erase(k, J.x_m[k], J.y_m[k]);
    };
    for (std::size_t k = 0; k < n; ++k) place(k);
    std::uint64_t work = 0;
    // visit(b) for each living disc b that overlaps disc k, as first_overlap tests it.
    const auto for_each_overlap = [&](std::size_t k, auto&& visit) {
      const auto test = [&](std::size_t b) {
        ++work;
        if (b != k && alive[b] && std::hypot(J.x_m[k] - J.x_m[b], J.y_m[k] - J.y_m[b]) < r[k] + r[b]) visit(b);
        return true;
      };
      const double rings = std::floor((r[k] + 0.5 * h) / h) + 1;
      grid.for_each_near(J.x_m[k], J.y_m[k], static_cast<std::int64_t>(std::min(rings, 1e9)), test);
      for (const std::size_t b : big) test(b);
      if (work > max_work) throw std::length_error("merge_overlapping_junctions: more than the work allowed");
    };
    std::set<std::size_t> pending;  // discs that may overlap one of a higher index
    for (std::size_t k = 0; k < n; ++k)
      for_each_overlap(k, [&](std::size_t b) {
        if (b > k) pending.insert(k);
      });
    using CellKey = std::tuple<std::int64_t, std::int64_t, std::size_t>;
    while (!pending.empty()) {
      const std::size_t i = *pending.begin();
      // The scan's grid: cells of the largest diameter (no smaller than 1e-12 of the extent).
      const double cell = std::max(2 * r_max, *reach.rbegin() * 1e-12);
      const auto cell_of = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
      std::optional<CellKey> first;
      for_each_overlap(i, [&](std::size_t b) {
        if (b < i) return;
        const CellKey key{cell_of(J.x_m[b]), cell_of(J.y_m[b]), b};
        if (!first || key < *first) first = key;
      });
      if (!first) {
        pending.erase(pending.begin());
        continue;
      }
      const std::size_t j = std::get<2>(*first);
      unplace(i), unplace(j);
      reach.erase(reach.find(reach_of(i))), reach.erase(reach.find(reach_of(j)));
      const double A = J.area_m2[i] + J.area_m2[j];
      J.x_m[i] = (J.area_m2[i] * J.x_m[i] + J.area_m2[j] * J.x_m[j]) / A;
      J.y_m[i] = (J.area_m2[i] * J.y_m[i] + J.area_m2[j] * J.y_m[j]) / A;
      J.area_m2[i] = A;
      r[i] = disc_radius(A);
      r_max = std::max(r_max, r[i]);
      alive[j] = 0;
      pending.erase(j);
      reach.insert(reach_of(i));
      place(i);
      ++merges;
      // The grown disc may overlap discs of lower index (now pending) and of higher.
      bool higher = false;
      for_each_overlap(i, [&](std::size_t b) {
        if (b < i)
          pending.insert(b);
        else
          higher = true;
      });
      if (!higher) pending.erase(i);
    }
  }
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < n; ++k)
    if (alive[k]) order.push_back(k);
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

TopographyContact solve_topography_contact(const TopographyRecipe& r, int threads, NormalContact* normal) {
  return solve_surface_contact(topography_surface(r), r, threads, normal);
}

TopographyContact solve_surface_contact(HeightMap map, const TopographyRecipe& r, int threads, NormalContact* normal) {
  TopographyContact t;
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
                         " iterations (residual " + io::format_short(c.residual) + " > tolerance " + num(r.tolerance) +
                         "); raise contact.max_iterations or contact.tolerance");
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
  try {
    t.merges = merge_overlapping_junctions(t.junctions);
  } catch (const std::length_error&) {
    throw InputError(r.display, r.topography_line, "topography",
                     "merging the overlapping discs of the " + std::to_string(t.clusters) +
                         " contact clusters needs more than " + io::format_short(static_cast<double>(kMaxMergeWork)) +
                         " disc comparisons: use contact.connectivity 8 or a coarser map");
  }
  // The junctions must pass what a junctions file's rows pass (what generate writes is read back
  // as one): a pixel of 1e-11 m or a map of 1e5 m pixels makes areas no command accepts.
  const JunctionPopulation& J = t.junctions;
  for (std::size_t i = 0; i < J.size(); ++i) {
    std::string why = junction_area_problem(J.area_m2[i]);
    for (const double v : {J.x_m[i], J.y_m[i]})
      if (why.empty()) why = junction_coordinate_problem(v);
    if (!why.empty())
      throw InputError(r.display, r.topography_line, "topography",
                       "junction " + std::to_string(i + 1) + " of the " + std::to_string(J.size()) +
                           " this surface makes: " + why + " (the map's pixel size, load_N and sphere_radius_m " +
                           "set the junctions' sizes)");
  }
  if (normal) *normal = std::move(c);
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
