// scene/topography_*.hpp: a scene whose junctions come from a topography recipe. Named or inline,
// it gives exactly the experiment `generate` writes; its recipe numbers are scene keys (--set,
// typed variants, campaign axes) and a sweep solves each distinct surface once; bad keys are one
// line; the scene written back reloads to the same run; a smooth sphere through a scene follows
// Hertz's area ∝ P^(2/3).
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "campaign/campaign_load.hpp"
#include "campaign/sweep.hpp"
#include "generate/topography.hpp"
#include "io/input_error.hpp"
#include "scene/load.hpp"
#include "scene/topography_cache.hpp"
#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;
using asperity::testing::fresh_dir;
using asperity::testing::slurp;
using asperity::testing::write_text;

namespace {

// 64² self-affine surface on a sphere of R = 10 mm, P = 1 N: ~10 clusters (test_generate_topography).
const char* kSurface =
    "self_affine:\n"
    "  seed: 7\n"
    "  n: 64\n"
    "  size_m: 5e-3\n"
    "  hurst: 0.8\n"
    "  rolloff_wavelength_m: 1.25e-3\n"
    "  short_wavelength_m: 3.125e-4\n"
    "  rms_height_m: 4e-5\n";
const char* kRest =
    "sphere_radius_m: 0.01\n"
    "E: 1.6e6\n"
    "nu: 0.5\n"
    "load_N: 1\n"
    "contact: {tolerance: 1e-10, max_iterations: 2000, connectivity: 8}\n";

std::string indented(const std::string& text, const std::string& pad) {
  std::string out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t nl = text.find('\n', at);
    out += pad + text.substr(at, nl - at) + "\n";
    at = nl + 1;
  }
  return out;
}

// The recipe file (its surface under `topography:`) and a short run of it.
const std::string kRecipe = "name: topo-scene\ntopography:\n" + indented(kSurface, "  ") + kRest;
const std::string kRun = "stop: {time: 0.05}\noutput: {every: 0.001, series: []}\n";

std::string error_of(const fs::path& scene, const std::vector<std::string>& sets = {}) {
  try {
    load_scene(scene, sets);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("a scene naming a recipe gives the experiment generate writes, exactly", "[scene][topography]") {
  const fs::path d = fresh_dir("asperity-scene-topo-same");
  write_text(d / "topo.yaml", kRecipe);
  const TopographyRecipe r = load_topography_recipe(d / "topo.yaml");
  write_topography_experiment(r, build_topography_junctions(r), d / "generated");
  const Experiment g = load_experiment(d / "generated" / "experiment.yaml");
  REQUIRE(g.junctions.size() >= 5);

  write_text(d / "named.yaml", "topography: topo.yaml\n" + kRun);
  write_text(d / "inline.yaml",
             "topography:\n  name: topo-scene\n" + indented(kSurface, "  ") + indented(kRest, "  ") + kRun);
  for (const char* file : {"named.yaml", "inline.yaml"}) {
    INFO(file);
    const Scene s = load_scene(d / file);
    REQUIRE(s.topography);
    const Experiment& e = s.experiment;
    CHECK(e.junctions.area_m2 == g.junctions.area_m2);  // bit for bit, through the CSV's text
    CHECK(e.junctions.x_m == g.junctions.x_m);
    CHECK(e.junctions.y_m == g.junctions.y_m);
    CHECK(e.name == g.name);
    CHECK(e.mass_kg == g.mass_kg);
    CHECK(e.k_L == g.k_L);
    CHECK(e.v == g.v);
    CHECK(e.E == g.E);
    CHECK(e.nu == g.nu);
    CHECK(e.sigma_exp == g.sigma_exp);
  }
  fs::remove_all(d);
}

TEST_CASE("a smooth sphere through a scene: Hertz's area at two loads of a typed variant", "[scene][topography]") {
  const fs::path d = fresh_dir("asperity-scene-topo-hertz");
  write_text(d / "smooth.yaml",
             "topography:\n  smooth: {n: 128, size_m: 5e-3}\n  sphere_radius_m: 0.01\n  E: 1.6e6\n  nu: 0.5\n"
             "  load_N: 1\n" +
                 kRun);
  auto cache = std::make_shared<TopographyCache>();
  const TypedScene typed = typed_scene_from_tree(load_scene_tree(d / "smooth.yaml"), d / "smooth.yaml", cache);
  const double E_star = 1.6e6 / (1 - 0.25);
  for (const double P : {1.0, 2.0}) {
    const Scene s = typed.with({{find_scene_key("topography.load_N"), P}});
    REQUIRE(s.experiment.junctions.size() == 1);
    const double a = std::cbrt(3 * P * 0.01 / (4 * E_star));  // Hertz: 1.52 mm at 1 N, 1.92 mm at 2 N
    const double A = s.experiment.junctions.area_m2[0];
    INFO("P = " << P << " N: A = " << A << " m^2, Hertz " << std::numbers::pi * a * a);
    // Pixel-wise contact edge: +0.83 % measured at 1 N and 128² (test_generate_topography).
    CHECK(std::abs(A / (std::numbers::pi * a * a) - 1) < 0.01);
    CHECK(s.experiment.mass_kg == P / 9.81);  // the slider follows the load (M = P/g)
  }
  CHECK(cache->solves() == 2);  // the base (1 N) and 2 N; the 1 N variant was the base's solve
  fs::remove_all(d);
}

TEST_CASE("a 2x2 sweep over a surface axis and a model axis solves each surface once",
          "[scene][topography][campaign]") {
  const fs::path d = fresh_dir("asperity-scene-topo-sweep");
  write_text(d / "topo.yaml", kRecipe);
  write_text(d / "scene.yaml", "topography: topo.yaml\n" + kRun);
  write_text(
      d / "sweep.yaml",
      "name: topo-sweep\nscenes: [scene.yaml]\n"
      "grids:\n  - name: g\n    axes:\n      topography.self_affine.hurst: [0.6, 0.8]\n      model.eta: [50, 100]\n");
  const Campaign c = load_campaign(d / "sweep.yaml");
  REQUIRE(c.topography);
  SweepOptions o;
  o.out = d / "store";
  o.threads = 2;
  o.quiet = true;
  const SweepReport rep = run_sweep(c, o);
  CHECK(rep.ran == 4);
  CHECK(rep.failed == 0);
  // H = 0.8 (the base scene's, and an axis value) and H = 0.6: two contact solves for the
  // campaign's checks, its store set-up and its four points.
  CHECK(c.topography->solves() == 2);
  const std::string points = slurp(d / "store" / "points.csv");
  CHECK(points.find("topography.self_affine.hurst") != std::string::npos);
  // A resume recognises every point without solving again.
  const SweepReport again = run_sweep(c, o);
  CHECK(again.skipped == 4);
  CHECK(again.ran == 0);
  CHECK(c.topography->solves() == 2);
  fs::remove_all(d);
}

TEST_CASE("topography scenes: bad keys and values are one line naming file, line and key", "[scene][topography]") {
  const fs::path d = fresh_dir("asperity-scene-topo-bad");
  write_text(d / "topo.yaml", kRecipe);
  std::string surface = indented(kSurface, "  ");
  surface.replace(surface.find("hurst"), 5, "hurts");
  write_text(d / "bad.yaml", "topography:\n" + surface + indented(kRest, "  ") + kRun);
  const std::string e1 = error_of(d / "bad.yaml");
  INFO(e1);
  CHECK(e1.rfind((d / "bad.yaml").string() + ":6: topography.self_affine.hurts: ", 0) == 0);
  CHECK(e1.find("hurst") != std::string::npos);  // did you mean
  CHECK(e1.find('\n') == std::string::npos);
  write_text(d / "named.yaml", "topography: topo.yaml\n" + kRun);
  CHECK(error_of(d / "named.yaml", {"topography.self_affine.hurst=1.5"}) ==
        "--set topography.self_affine.hurst=1.5: topography.self_affine.hurst: must be in (0, 1), got 1.5");
  write_text(d / "both.yaml", "experiment: x.yaml\ntopography: topo.yaml\n");
  CHECK(error_of(d / "both.yaml") == (d / "both.yaml").string() +
                                         ":1: experiment: give either experiment or topography (which makes the "
                                         "experiment), not both");
  // A typed variant: the key table's range, naming the scene file.
  const TypedScene typed = typed_scene_from_tree(load_scene_tree(d / "named.yaml"), d / "named.yaml");
  try {
    typed.with({{find_scene_key("topography.self_affine.hurst"), 1.0}});
    FAIL("no error");
  } catch (const io::InputError& e) {
    CHECK(std::string(e.what()) ==
          (d / "named.yaml").string() + ": topography.self_affine.hurst: must be in (0, 1), got 1");
  }
  fs::remove_all(d);
}

TEST_CASE("a topography scene written back reloads to the same run", "[scene][topography]") {
  const fs::path d = fresh_dir("asperity-scene-topo-write");
  write_text(d / "topo.yaml", kRecipe);
  write_text(d / "scene.yaml", "topography: topo.yaml\n" + kRun);
  // A variant with another surface (rms slope instead of rms height) and load, set through --set.
  const Scene s = load_scene(d / "scene.yaml", {"topography.self_affine.rms_slope=0.2", "topography.load_N=0.8",
                                                "topography.slider.k_L=9000", "model.eta=60"});
  REQUIRE(s.topography);
  CHECK(s.topography->self_affine.rms_height_m == 0);
  CHECK(s.experiment.k_L == 9000);
  const std::string text = scene_to_yaml(s);
  CHECK(text.find("experiment:") == std::string::npos);
  CHECK(text.find("    rms_slope: 0.2\n") != std::string::npos);
  const fs::path other = write_text(d / "elsewhere" / "scene.yaml", text);
  const Scene back = load_scene(other);
  CHECK(scene_to_yaml(back) == text);
  CHECK(back.experiment.junctions.area_m2 == s.experiment.junctions.area_m2);
  CHECK(back.experiment.junctions.x_m == s.experiment.junctions.x_m);
  CHECK(back.experiment.mass_kg == s.experiment.mass_kg);
  CHECK(back.model.eta == 60);
  fs::remove_all(d);
}
