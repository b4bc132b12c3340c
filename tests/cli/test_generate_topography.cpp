// generate/topography.hpp: junctions from topography. Overlapping equivalent discs are merged
// (area conserved, area-weighted centroid, cascades), a smooth sphere gives Hertz's contact as one
// junction, the recipe gives the same bytes twice (synthetic or the same heights read from a
// measured map), bad recipes are refused at their line, and the experiment written runs.
#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_spawn.hpp"
#include "generate/topography.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "scene/validate.hpp"
#include "studies/continuum_rule.hpp"
#include "support_files.hpp"
#include "surface/height_map_io.hpp"
#include "surface/segmentation.hpp"

using namespace asperity;
namespace fs = std::filesystem;
using asperity::testing::fresh_dir;
using asperity::testing::run_argv;
using asperity::testing::slurp;
using asperity::testing::write_text;

namespace {

// A recipe for a sphere of R = 10 mm on a 5 mm wide map, E = 1.6 MPa, ν = 0.5 (the paper's
// elastomer), P = 1 N: Hertz's a = 1.52 mm, ~39 pixels at 128².
std::string recipe_text(const std::string& topography) {
  return "name: topo-test\n"
         "topography:\n" +
         topography +
         "sphere_radius_m: 0.01\n"
         "E: 1.6e6\n"
         "nu: 0.5\n"
         "load_N: 1\n"
         "contact:\n"
         "  tolerance: 1e-10\n"
         "  max_iterations: 2000\n"
         "  connectivity: 8\n";
}

const char* kSelfAffine =
    "  self_affine:\n"
    "    seed: 7\n"
    "    n: 64\n"
    "    size_m: 5e-3\n"
    "    hurst: 0.8\n"
    "    rolloff_wavelength_m: 1.25e-3\n"
    "    short_wavelength_m: 3.125e-4\n"
    "    rms_height_m: 4e-5\n";  // rough enough for 10 clusters, two of which merge (measured)

std::string load_error(const fs::path& dir, const std::string& text) {
  write_text(dir / "bad.yaml", text);
  try {
    load_topography_recipe(dir / "bad.yaml");
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

// The data lines of a junctions CSV (its provenance header left out).
std::string data_lines(const std::string& csv) { return csv.substr(csv.find("area_m2,x_m,y_m\n")); }

}  // namespace

TEST_CASE("overlapping junction discs are merged, area conserved, until none overlap", "[generate][topography]") {
  const double pi = std::numbers::pi;
  // A (r = 1) and B (r = 1) overlap; C (r = 0.5) overlaps neither but overlaps their merged disc
  // (r = √2 at (0.95, 0), 1.9 away < 1.914); D is far away and stays.
  JunctionPopulation J;
  J.area_m2 = {pi, pi, 0.25 * pi, 0.01};
  J.x_m = {0, 1.9, 0.95, 10};
  J.y_m = {0, 0, 1.9, 10};
  REQUIRE(first_overlap(J));
  const std::size_t merges = merge_overlapping_junctions(J);
  CHECK(merges == 2);
  REQUIRE(J.size() == 2);
  CHECK(J.area_m2[0] == Approx(2.25 * pi).epsilon(1e-15));
  CHECK(J.x_m[0] == Approx(0.95).epsilon(1e-15));
  CHECK(J.y_m[0] == Approx(0.25 * 1.9 / 2.25).epsilon(1e-15));
  CHECK(J.area_m2[1] == 0.01);
  CHECK(J.x_m[1] == 10);
  CHECK_FALSE(first_overlap(J));
  // Touching discs (d = r1 + r2) are separate junctions, as first_overlap has it.
  JunctionPopulation T{{pi, pi}, {0, 2}, {0, 0}};
  CHECK(merge_overlapping_junctions(T) == 0);
  CHECK(T.size() == 2);
}

namespace {

// The merge as first written, one pair per full scan (O(N^2)): the reference the indexed merge
// must equal bit for bit.
std::size_t merge_one_pair_per_scan(JunctionPopulation& J) {
  std::size_t merges = 0;
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

// The clusters (4-connectivity) of an n x n map: a square ring one pixel in from the edge around
// a checkerboard of single pixels filling the middle half, the ring's disc overlapping many.
JunctionPopulation ring_and_checkerboard(std::size_t n) {
  std::vector<unsigned char> mask(n * n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t edge = std::min({i, j, n - 1 - i, n - 1 - j});
      const bool middle = i >= n / 4 && i < 3 * n / 4 && j >= n / 4 && j < 3 * n / 4;
      mask[i * n + j] = edge == 1 || (middle && (i + j) % 2 == 0);
    }
  JunctionPopulation J;
  for (const ContactCluster& c : contact_clusters(mask, n, 1e-6, Connectivity::four)) {
    J.area_m2.push_back(c.area_m2);
    J.x_m.push_back(c.x_m);
    J.y_m.push_back(c.y_m);
  }
  return J;
}

}  // namespace

TEST_CASE("the indexed merge of overlapping discs equals the one-pair-per-scan merge, bit for bit",
          "[generate][topography]") {
  // Random discs of sizes over two decades, dense enough for cascades, and a map's clusters.
  std::mt19937_64 rng(20260428);
  std::vector<JunctionPopulation> cases;
  for (const std::size_t n : {2, 40, 400, 3000}) {
    JunctionPopulation J;
    std::uniform_real_distribution<double> at(-1.0, 1.0), log_r(std::log(0.002), std::log(0.2));
    for (std::size_t k = 0; k < n; ++k) {
      const double r = std::exp(log_r(rng)) * 10 / std::sqrt(static_cast<double>(n));
      J.area_m2.push_back(std::numbers::pi * r * r);
      J.x_m.push_back(at(rng));
      J.y_m.push_back(at(rng));
    }
    cases.push_back(J);
  }
  cases.push_back(ring_and_checkerboard(64));
  std::size_t total_merges = 0;
  for (const JunctionPopulation& start : cases) {
    INFO(start.size() << " discs");
    JunctionPopulation fast = start, slow = start;
    const std::size_t m = merge_overlapping_junctions(fast);
    CHECK(m == merge_one_pair_per_scan(slow));
    CHECK(fast.area_m2 == slow.area_m2);  // exactly: the same merges in the same order
    CHECK(fast.x_m == slow.x_m);
    CHECK(fast.y_m == slow.y_m);
    CHECK_FALSE(first_overlap(fast));
    total_merges += m;
  }
  CHECK(cases.back().size() == 1 + 32 * 32 / 2);  // the ring and 512 single pixels
  CHECK(total_merges > 500);                      // cascades happened
  // The phase is bounded: past the work allowed, std::length_error.
  JunctionPopulation J = cases.back();
  CHECK_THROWS_AS(merge_overlapping_junctions(J, 1000), std::length_error);
}

TEST_CASE("bench: merging the discs of a 1024^2 ring around a checkerboard (prints the time)",
          "[.][bench][topography]") {
  JunctionPopulation J = ring_and_checkerboard(1024);
  const std::size_t clusters = J.size();
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t merges = merge_overlapping_junctions(J);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("1024^2 ring + checkerboard (4-connectivity): %zu clusters, %zu merges, %zu junctions, %.3f s\n",
              clusters, merges, J.size(), s);
  CHECK(J.size() + merges == clusters);
}

TEST_CASE("a smooth sphere gives one junction of Hertz's area", "[generate][topography]") {
  const fs::path d = fresh_dir("asperity-topo-hertz");
  write_text(d / "smooth.yaml", recipe_text("  smooth:\n    n: 128\n    size_m: 5e-3\n"));
  const TopographyRecipe r = load_topography_recipe(d / "smooth.yaml");
  const TopographyJunctions t = build_topography_junctions(r);
  REQUIRE(t.experiment.junctions.size() == 1);
  CHECK(t.clusters == 1);
  CHECK(t.merges == 0);
  const double E_star = 1.6e6 / (1 - 0.25);
  const double a = std::cbrt(3 * 1.0 * 0.01 / (4 * E_star));  // 1.5207 mm = 38.9 pixels
  const double hertz = std::numbers::pi * a * a;
  const double A = t.experiment.junctions.area_m2[0];
  // Pixels counted in contact against π a² (7.2636e-6 m²): measured +0.83 % at 128² (4800
  // pixels of 39.06 µm; a = 38.9 pixels), +1.51 % at 64², +0.35 % at 256²: first order in the
  // pixel, as a pixel-wise contact edge is. The bound is one ring of pixels, 2 px / a = 5.1 %;
  // the second check holds the measured value with a little margin.
  INFO("A = " << A << " m^2, Hertz " << hertz << " m^2, relative error " << (A / hertz - 1));
  CHECK(std::abs(A / hertz - 1) < 2 * r.pixel_m / a);
  CHECK(std::abs(A / hertz - 1) < 0.01);  // what is measured, with margin
  // Symmetric about the grid's centre.
  CHECK(std::abs(t.experiment.junctions.x_m[0]) < 1e-9 * r.pixel_m);
  CHECK(std::abs(t.experiment.junctions.y_m[0]) < 1e-9 * r.pixel_m);
  CHECK(t.experiment.mass_kg == 1 / 9.81);  // P / g, the paper's slider otherwise
  CHECK(t.experiment.k_L == 9200);
  CHECK(t.experiment.sigma_exp == 0.23e6);
  const std::string csv = topography_junctions_csv(r, t);
  CHECK(csv.find("# surface: a smooth sphere (no roughness), generated from a synthetic surface\n") !=
        std::string::npos);
  CHECK(csv.find("# junctions: 1, total area_m2: ") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("topography recipes: bad values refused at their line", "[generate][topography]") {
  const fs::path d = fresh_dir("asperity-topo-bad");
  CHECK(load_error(d, recipe_text("  smooth:\n    n: 64\n    size_m: 5e-3\n  file: map.csv\n")) ==
        (d / "bad.yaml").string() + ":3: topography.file: give exactly one of smooth, self_affine and file");
  CHECK(load_error(d, recipe_text("  smooth:\n    n: 9000\n    size_m: 5e-3\n")) ==
        (d / "bad.yaml").string() + ":4: topography.smooth.n: must be in [2, 8192], got 9000");
  CHECK(load_error(d, recipe_text("  file: map.csv\n  pixel_m: 1e-6\n"))
            .rfind((d / "bad.yaml").string() + ":3: topography.file: height map not found: 'map.csv'", 0) == 0);
  std::string c6 = recipe_text("  smooth:\n    n: 64\n    size_m: 5e-3\n");
  c6.replace(c6.find("connectivity: 8"), 15, "connectivity: 6");
  CHECK(load_error(d, c6) == (d / "bad.yaml").string() + ":13: contact.connectivity: must be 4 or 8, got 6");
  // Found by the solve: a contact wider than the map (Hertz's a = 1.52 mm on a 2 mm map), and a
  // solve stopped before its tolerance.
  const auto build_error = [&](const std::string& text) {
    write_text(d / "bad.yaml", text);
    try {
      build_topography_junctions(load_topography_recipe(d / "bad.yaml"));
    } catch (const io::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(build_error(recipe_text("  smooth:\n    n: 32\n    size_m: 2e-3\n")) ==
        (d / "bad.yaml").string() +
            ":3: topography: the contact reaches the edge of the 32 x 32 map: enlarge the map (or lower load_N, or "
            "the sphere_radius_m)");
  // A float64 map with a spike of 1e308 m (or a pit): refused at its header's data key, naming
  // the height, before the contact solve (which broke down on it: exit 1).
  for (const double spike : {1e308, -1e308}) {
    HeightMap m;
    m.n = 16;
    m.pixel_m = 3e-4;
    m.h_m.assign(m.n * m.n, 0.0);
    m.h_m[3 * m.n + 5] = spike;
    write_height_map_binary(d / "spike.yaml", "spike.f64", m);
    const std::string expected = (d / "spike.yaml").string() + ":3: data: row 4, column 6 of " +
                                 (d / "spike.f64").string() + ": height " + io::format_double(spike) +
                                 " m: the heights span 1e+308 m";
    CHECK(build_error(recipe_text("  file: spike.yaml\n")).rfind(expected, 0) == 0);
  }
  std::string once = recipe_text("  smooth:\n    n: 64\n    size_m: 5e-3\n");
  once.replace(once.find("max_iterations: 2000"), 20, "max_iterations: 1");
  CHECK(build_error(once).rfind(
            (d / "bad.yaml").string() + ": contact.max_iterations: the normal contact did not converge in 1 iterations",
            0) == 0);
  fs::remove_all(d);
}

TEST_CASE("topography recipe: same bytes twice, measured map = synthetic heights, the experiment runs",
          "[generate][topography][cli]") {
  const fs::path d = fresh_dir("asperity-topo-cli");
  write_text(d / "topo.yaml", recipe_text(kSelfAffine));
  auto r1 = run_argv(d, {"generate", "--recipe", "topo.yaml", "--out", "one", "--quiet"});
  auto r2 = run_argv(d, {"generate", "--recipe", "topo.yaml", "--out", "two", "--quiet"});
  INFO(r1.err << r2.err);
  REQUIRE(r1.status == 0);
  REQUIRE(r2.status == 0);
  const std::string csv = slurp(d / "one/junctions.csv");
  CHECK(csv == slurp(d / "two/junctions.csv"));
  CHECK(slurp(d / "one/experiment.yaml") == slurp(d / "two/experiment.yaml"));
  CHECK(csv.find("generated from a synthetic surface") != std::string::npos);
  CHECK(csv.find("# seed: 7\n") != std::string::npos);
  CHECK(csv.find("# recipe_sha256: ") != std::string::npos);
  CHECK(csv.find("# clusters: 10 (connectivity 8), merges of overlapping equivalent discs: 1\n") != std::string::npos);
  CHECK(csv.find("# junctions: 9, total area_m2: ") != std::string::npos);
  // Again into the same folder (ours, by its marker): same bytes.
  REQUIRE(run_argv(d, {"generate", "--recipe", "topo.yaml", "--out", "one", "--quiet"}).status == 0);
  CHECK(slurp(d / "one/junctions.csv") == csv);
  // An edited output is not replaced: refused by name, the edit kept.
  const std::string experiment = slurp(d / "one/experiment.yaml");
  write_text(d / "one/experiment.yaml", experiment + "# k_L edited by hand\n");
  const auto edited = run_argv(d, {"generate", "--recipe", "topo.yaml", "--out", "one", "--quiet"});
  CHECK(edited.status == 2);
  CHECK(edited.err.rfind((d / "one/experiment.yaml").string() + ": --out: refusing to replace it", 0) == 0);
  CHECK(slurp(d / "one/experiment.yaml") == experiment + "# k_L edited by hand\n");
  write_text(d / "one/experiment.yaml", experiment);

  // The same heights as a measured map (CSV and float64) give the same junctions.
  const TopographyRecipe r = load_topography_recipe(d / "topo.yaml");
  const HeightMap map = topography_surface(r);
  write_height_map_csv(d / "map.csv", map);
  write_height_map_binary(d / "map.yaml", "map.f64", map);
  write_text(d / "measured_csv.yaml",
             recipe_text("  file: map.csv\n  pixel_m: " + io::format_double(map.pixel_m) + "\n"));
  write_text(d / "measured_bin.yaml", recipe_text("  file: map.yaml\n"));
  REQUIRE(run_argv(d, {"generate", "--recipe", "measured_csv.yaml", "--out", "mcsv", "--quiet"}).status == 0);
  REQUIRE(run_argv(d, {"generate", "--recipe", "measured_bin.yaml", "--out", "mbin", "--quiet"}).status == 0);
  CHECK(data_lines(slurp(d / "mcsv/junctions.csv")) == data_lines(csv));
  CHECK(data_lines(slurp(d / "mbin/junctions.csv")) == data_lines(csv));
  CHECK(slurp(d / "mcsv/junctions.csv").find("# surface: measured height map map.csv\n") != std::string::npos);

  // The experiment runs, with elastic interactions (which need the discs apart).
  write_text(d / "scene.yaml",
             "experiment: one/experiment.yaml\nmodel:\n  interactions: elastic\nstop:\n  time: 0.02\n"
             "output:\n  every: 0.001\n");
  const auto run = run_argv(d, {"run", "scene.yaml", "--out", "run", "--quiet"});
  INFO(run.err);
  CHECK(run.status == 0);
  fs::remove_all(d);
}

TEST_CASE("the committed topography example regenerates byte for byte", "[generate][topography][cli]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path d = fresh_dir("asperity-topo-example");
  const auto r = run_argv(
      d, {"generate", "--recipe", (src / "examples/topography/topo.yaml").string(), "--out", "generated", "--quiet"});
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(slurp(d / "generated/junctions.csv") == slurp(src / "examples/topography/generated/junctions.csv"));
  CHECK(slurp(d / "generated/experiment.yaml") == slurp(src / "examples/topography/generated/experiment.yaml"));
  fs::remove_all(d);
}

TEST_CASE("run: independent junctions with positions get the continuum rule's estimate, interacting ones none",
          "[generate][topography][cli]") {
  // The estimate is the committed rule (studies/continuum_rule.hpp) at the population's stiffness
  // ratio, computed here from the junctions file independently of the command.
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path d = fresh_dir("asperity-run-advice");
  const std::string scene = (src / "examples/topography/scene.yaml").string();
  const auto indep = run_argv(d, {"run", scene, "--set", "model.interactions=none", "--out", "a"});
  INFO(indep.err);
  REQUIRE(indep.status == 0);
  std::vector<double> A, x, y;
  {
    std::istringstream in(slurp(src / "examples/topography/generated/junctions.csv"));
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#' || line[0] == 'a') continue;
      double a = 0, px = 0, py = 0;
      char c1 = 0, c2 = 0;
      std::istringstream(line) >> a >> c1 >> px >> c2 >> py;
      A.push_back(a), x.push_back(px), y.push_back(py);
    }
  }
  double S = 0, cx = 0, cy = 0, radii = 0, rg2 = 0;
  for (std::size_t i = 0; i < A.size(); ++i) S += A[i], cx += A[i] * x[i], cy += A[i] * y[i];
  cx /= S, cy /= S;
  for (std::size_t i = 0; i < A.size(); ++i)
    rg2 += A[i] * ((x[i] - cx) * (x[i] - cx) + (y[i] - cy) * (y[i] - cy)), radii += std::sqrt(A[i] / M_PI);
  const double ratio = radii / std::sqrt(2 * rg2 / S);
  const StiffnessRule rule = independent_stiffness_rule();
  char expected[160];
  std::snprintf(expected, sizeof expected, "estimated stiffness error %.0f %% at stiffness ratio %.3g",
                100 * rule.error_at(ratio), ratio);
  INFO(indep.out);
  CHECK(indep.out.find(expected) != std::string::npos);
  const auto inter = run_argv(d, {"run", scene, "--out", "b"});
  REQUIRE(inter.status == 0);
  CHECK(inter.out.find("independent junctions:") == std::string::npos);
  fs::remove_all(d);
}
