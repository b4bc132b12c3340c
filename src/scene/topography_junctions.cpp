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

std::string heights_sha256(const HeightMap& m) {
  io::Sha256 h;
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
             std::to_string(a.seed) + ", hurst " + io::format_double(a.hurst) + ", rolloff_wavelength_m " +
             (a.rolloff_wavelength_m > 0 ? io::format_double(a.rolloff_wavelength_m) : "none (= size)") +
             ", short_wavelength_m " +
             (a.short_wavelength_m > 0 ? io::format_double(a.short_wavelength_m) : "2 pixels") +
             (a.rms_height_m > 0 ? ", rms_height_m " + io::format_double(a.rms_height_m)
                                 : ", rms_slope " + io::format_double(a.rms_slope));
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
        throw io::InputError(r.display, r.topography_line, "topography.self_affine", e.what());
      }
    case TopographyKind::measured:
      if (r.map_file.extension() == ".csv")
        return read_height_map_csv(r.map_file, io::input_path(r.map_file), r.pixel_m);
      return read_height_map_binary(r.map_file, io::input_path(r.map_file));
  }
  throw std::logic_error("topography_surface: unknown kind");
}

namespace {

// Merges the overlapping discs of a population (two or more junctions, with positions) in place.
// The pair merged next is the one a full scan would find first (scene/validate.cpp first_overlap:
// the lowest index with an overlapping disc of a higher index, and of those discs the first in its
// grid's cell order), so the result is that of merging one pair per scan; only the discs a merge
// changed are looked at again. A junction keeps its index (the lower of a pair lives on, as the
// erase of the other kept it), so index order is the scan's.
class DiscMerger {
 public:
  DiscMerger(JunctionPopulation& J, std::uint64_t max_work)
      : J_(J),
        n_(J.size()),
        max_work_(max_work),
        alive_(n_, 1),
        r_(radii(J)),
        reach_(reaches(J)),
        r_max_(*std::max_element(r_.begin(), r_.end())),
        grid_(2 * median(r_), *reach_.rbegin()),
        h_(grid_.cell()) {
    for (std::size_t k = 0; k < n_; ++k) place(k);
  }

  // Merges pairs until no disc overlaps another; returns the count of merges.
  std::size_t merge_all() {
    for (std::size_t k = 0; k < n_; ++k)
      for_each_overlap(k, [&](std::size_t b) {
        if (b > k) pending_.insert(k);
      });
    std::size_t merges = 0;
    while (!pending_.empty()) {
      const std::size_t i = *pending_.begin();
      const std::optional<std::size_t> j = first_partner(i);
      if (!j) {
        pending_.erase(pending_.begin());
        continue;
      }
      merge_pair(i, *j);
      ++merges;
      requeue(i);
    }
    return merges;
  }

  const std::vector<unsigned char>& alive() const { return alive_; }

 private:
  static std::vector<double> radii(const JunctionPopulation& J) {
    std::vector<double> r(J.size());
    for (std::size_t k = 0; k < J.size(); ++k) r[k] = disc_radius(J.area_m2[k]);
    return r;
  }
  static double reach_of(const JunctionPopulation& J, std::size_t k) {
    return std::max(std::abs(J.x_m[k]), std::abs(J.y_m[k]));
  }
  static std::multiset<double> reaches(const JunctionPopulation& J) {
    std::multiset<double> reach;
    for (std::size_t k = 0; k < J.size(); ++k) reach.insert(reach_of(J, k));
    return reach;
  }
  static double median(std::vector<double> by_size) {
    const std::size_t n = by_size.size();
    std::nth_element(by_size.begin(), by_size.begin() + static_cast<std::ptrdiff_t>(n / 2), by_size.end());
    return by_size[n / 2];
  }

  // Discs of up to half a cell (twice the median radius) in a grid, searched in the cells their
  // radius reaches; the few larger ones (a merge grows them) apart, checked one by one.
  void place(std::size_t k) {
    if (2 * r_[k] > h_)
      big_.push_back(k);
    else
      grid_.insert(k, J_.x_m[k], J_.y_m[k]);
  }
  void unplace(std::size_t k) {
    if (2 * r_[k] > h_)
      big_.erase(std::find(big_.begin(), big_.end(), k));
    else
      grid_.erase(k, J_.x_m[k], J_.y_m[k]);
  }

  // visit(b) for each living disc b that overlaps disc k, as first_overlap tests it.
  template <class Visit>
  void for_each_overlap(std::size_t k, Visit&& visit) {
    const auto test = [&](std::size_t b) {
      ++work_;
      if (b != k && alive_[b] && std::hypot(J_.x_m[k] - J_.x_m[b], J_.y_m[k] - J_.y_m[b]) < r_[k] + r_[b]) visit(b);
      return true;
    };
    const double rings = std::floor((r_[k] + 0.5 * h_) / h_) + 1;
    grid_.for_each_near(J_.x_m[k], J_.y_m[k], static_cast<std::int64_t>(std::min(rings, 1e9)), test);
    for (const std::size_t b : big_) test(b);
    if (work_ > max_work_) throw std::length_error("merge_overlapping_junctions: more than the work allowed");
  }

  // The disc of higher index than i that the scan would merge with i first, if any.
  std::optional<std::size_t> first_partner(std::size_t i) {
    using CellKey = std::tuple<std::int64_t, std::int64_t, std::size_t>;
    // The scan's grid: cells of the largest diameter (no smaller than 1e-12 of the extent).
    const double cell = std::max(2 * r_max_, *reach_.rbegin() * 1e-12);
    const auto cell_of = [&](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
    std::optional<CellKey> first;
    for_each_overlap(i, [&](std::size_t b) {
      if (b < i) return;
      const CellKey key{cell_of(J_.x_m[b]), cell_of(J_.y_m[b]), b};
      if (!first || key < *first) first = key;
    });
    if (!first) return std::nullopt;
    return std::get<2>(*first);
  }

  // Disc j joins disc i at their area-weighted centre.
  void merge_pair(std::size_t i, std::size_t j) {
    unplace(i), unplace(j);
    reach_.erase(reach_.find(reach_of(J_, i))), reach_.erase(reach_.find(reach_of(J_, j)));
    const double A = J_.area_m2[i] + J_.area_m2[j];
    J_.x_m[i] = (J_.area_m2[i] * J_.x_m[i] + J_.area_m2[j] * J_.x_m[j]) / A;
    J_.y_m[i] = (J_.area_m2[i] * J_.y_m[i] + J_.area_m2[j] * J_.y_m[j]) / A;
    J_.area_m2[i] = A;
    r_[i] = disc_radius(A);
    r_max_ = std::max(r_max_, r_[i]);
    alive_[j] = 0;
    pending_.erase(j);
    reach_.insert(reach_of(J_, i));
    place(i);
  }

  // The grown disc i may overlap discs of lower index (now pending) and of higher.
  void requeue(std::size_t i) {
    bool higher = false;
    for_each_overlap(i, [&](std::size_t b) {
      if (b < i)
        pending_.insert(b);
      else
        higher = true;
    });
    if (!higher) pending_.erase(i);
  }

  JunctionPopulation& J_;
  const std::size_t n_;
  const std::uint64_t max_work_;
  std::vector<unsigned char> alive_;
  std::vector<double> r_;
  std::multiset<double> reach_;  // of the living discs: the scan's grid extent
  double r_max_;
  NeighbourGrid grid_;
  const double h_;
  std::vector<std::size_t> big_;
  std::uint64_t work_ = 0;
  std::set<std::size_t> pending_;  // discs that may overlap one of a higher index
};

// The living junctions, largest first (ties: by x, then y).
JunctionPopulation living_by_size(const JunctionPopulation& J, const std::vector<unsigned char>& alive) {
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < J.size(); ++k)
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
  return sorted;
}

}  // namespace

std::size_t merge_overlapping_junctions(JunctionPopulation& J, std::uint64_t max_work) {
  if (J.x_m.size() != J.size() || J.y_m.size() != J.size())
    throw std::invalid_argument("merge_overlapping_junctions: junctions need positions");
  std::vector<unsigned char> alive(J.size(), 1);
  std::size_t merges = 0;
  if (J.size() >= 2) {
    DiscMerger merger(J, max_work);
    merges = merger.merge_all();
    alive = merger.alive();
  }
  J = living_by_size(J, alive);
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
    throw io::InputError(r.display, r.topography_line, "topography", e.what());
  }
  if (!c.converged)
    throw io::InputError(r.display, 0, r.file.empty() ? "topography.contact.max_iterations" : "contact.max_iterations",
                         "the normal contact did not converge in " + std::to_string(c.iterations) +
                             " iterations (residual " + io::format_short(c.residual) + " > tolerance " +
                             io::format_double(r.tolerance) + "); raise contact.max_iterations or contact.tolerance");
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
    throw io::InputError(r.display, r.topography_line, "topography",
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
    throw io::InputError(r.display, r.topography_line, "topography",
                         "merging the overlapping discs of the " + std::to_string(t.clusters) +
                             " contact clusters needs more than " +
                             io::format_short(static_cast<double>(kMaxMergeWork)) +
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
      throw io::InputError(r.display, r.topography_line, "topography",
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
  e.description =
      "Junctions from topography: the contact clusters of a sphere of R = " + io::format_double(r.sphere_radius_m) +
      " m on a rigid flat at P = " + io::format_double(r.load_N) + " N, merged where their equivalent discs overlap (" +
      std::to_string(t.clusters) + " clusters, " + std::to_string(e.junctions.size()) + " junctions); surface " +
      topography_surface_text(r) + ". " + made_by;
  return e;
}

}  // namespace asperity
