// Stand-in generator: recipe reading, measured curve, and byte-for-byte regeneration of the
// committed data/standin/ and scenes/paper/ files.
#include <catch2/catch.hpp>
#include <cmath>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include "scene/validate.hpp"

#include "generate/recipe.hpp"
#include "generate/standin.hpp"
#include "io/input_error.hpp"
#include "scene/load.hpp"

using namespace asperity;
namespace fs = std::filesystem;

namespace {

const fs::path kSource = ASPERITY_SOURCE_DIR;
const fs::path kRecipe = kSource / "data" / "standin" / "recipe.yaml";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& tag) {
    path = fs::temp_directory_path() / ("asperity_test_" + tag + "_" + std::to_string(std::random_device{}()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// A recipe file holding `text`; returns the InputError message of load_recipe ("" if none).
std::string recipe_error(const TempDir& dir, const std::string& text) {
  const fs::path p = dir.path / "recipe.yaml";
  std::ofstream(p, std::ios::binary) << text;
  try {
    load_recipe(p);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

const char* kMinimal =
    "seed: 1\n"
    "masses_kg: [0.1, 0.2]\n"
    "k_L: 9200\n"
    "v: 1e-4\n"
    "E: 1.6e6\n"
    "nu: 0.5\n"
    "sigma_exp: 0.23e6\n"
    "junctions_per_newton: 300\n"
    "distribution:\n"
    "  family: power_law\n"
    "  tau: 1.5\n"
    "  a_min: 1e-9\n"
    "  a_max: 1e-7\n"
    "measured:\n"
    "  alpha_b: 0.725e-15\n";

}  // namespace

TEST_CASE("stand-in folder names follow P{P:.2f}N", "[generate]") {
  CHECK(standin_name(0.100 * 9.81) == "P0.98N");
  CHECK(standin_name(0.155 * 9.81) == "P1.52N");
  CHECK(standin_name(0.211 * 9.81) == "P2.07N");
  CHECK(standin_name(0.315 * 9.81) == "P3.09N");
  CHECK(standin_name(0.408 * 9.81) == "P4.00N");
  CHECK(standin_name(0.652 * 9.81) == "P6.40N");
}

TEST_CASE("the committed recipe reads back with the paper's values", "[generate]") {
  const StandinRecipe r = load_recipe(kRecipe);
  REQUIRE(r.masses_kg.size() == 6);
  const double added[6] = {0, 0.055, 0.111, 0.215, 0.308, 0.552};
  for (int i = 0; i < 6; ++i)
    CHECK(r.masses_kg[static_cast<std::size_t>(i)] == Approx(0.100 + added[i]).epsilon(1e-15));
  CHECK(r.k_L == 9200);
  CHECK(r.v == 1e-4);
  CHECK(r.E == 1.6e6);
  CHECK(r.nu == 0.5);
  CHECK(r.sigma_exp == 0.23e6);
  CHECK(r.junctions_per_newton == 300);
  CHECK(r.drop_smallest == 0.15);
  CHECK(r.drop_largest == 0.25);
  CHECK(experiment_seed(r, 0) != experiment_seed(r, 1));
  CHECK(noise_seed(experiment_seed(r, 0)) != experiment_seed(r, 0));
}

TEST_CASE("recipe errors name file, line and key", "[generate]") {
  TempDir dir("recipe");
  CHECK(recipe_error(dir, kMinimal).empty());

  std::string e = recipe_error(dir, std::string(kMinimal) + "junction_per_newton: 3\n");
  CHECK_THAT(e, Catch::Contains("recipe.yaml:16: junction_per_newton: unknown key"));
  CHECK_THAT(e, Catch::Contains("did you mean 'junctions_per_newton'"));

  std::string bad = kMinimal;
  bad.replace(bad.find("family: power_law"), 17, "family: powerlaw");
  e = recipe_error(dir, bad);
  CHECK_THAT(e, Catch::Contains("recipe.yaml:10: distribution.family: unknown value 'powerlaw'"));

  bad = kMinimal;
  bad.replace(bad.find("  tau: 1.5"), 10, "  tau: 1.5\n  sigma_ln: 2");
  CHECK_THAT(recipe_error(dir, bad), Catch::Contains("recipe.yaml:12: distribution.sigma_ln: unknown key"));

  bad = kMinimal;
  bad.replace(bad.find("a_max: 1e-7"), 11, "a_max: 1e-10");
  CHECK_THAT(recipe_error(dir, bad), Catch::Contains("recipe.yaml:13: distribution.a_max: must be > a_min"));

  CHECK_THAT(recipe_error(dir, std::string(kMinimal) + "  colour: red\n"),
             Catch::Contains("recipe.yaml:16: measured.colour: unknown key"));
  CHECK_THAT(recipe_error(dir, std::string("seed: -3\n") + (kMinimal + 8)), Catch::Contains("recipe.yaml:1: seed:"));

  const std::string mix = std::string(kMinimal).substr(0, std::string(kMinimal).find("distribution:")) +
                          "distribution:\n"
                          "  family: mixture\n"
                          "  components:\n"
                          "    - {weight: 0.7, family: power_law, tau: 1.5, a_min: 1e-9, a_max: 1e-7}\n"
                          "    - {weight: 0.3, family: fixed, area: 3e-8, tau: 2}\n"
                          "measured:\n"
                          "  alpha_b: 0.725e-15\n";
  CHECK_THAT(recipe_error(dir, mix), Catch::Contains("recipe.yaml:13: distribution.components[1].tau: unknown key"));
}

TEST_CASE("stand-in measured curve: exact quadratic without noise, seeded noise otherwise", "[generate]") {
  const double A0 = 1e-5, Q_s = 2.0, alpha = 0.2 * A0 / (Q_s * Q_s);
  const MeasuredCurve c = standin_measured_curve(A0, Q_s, alpha, 60, 0.0, 1);
  REQUIRE(c.Q_N.size() == 60);
  CHECK(c.Q_N.front() == 0.0);
  CHECK(c.Q_N.back() == Q_s);
  CHECK(c.A_m2.front() == A0);
  CHECK(1.0 - c.A_m2.back() / A0 == Approx(0.2).epsilon(1e-12));
  const MeasuredCurve n1 = standin_measured_curve(A0, Q_s, alpha, 60, 0.002, 1);
  const MeasuredCurve n2 = standin_measured_curve(A0, Q_s, alpha, 60, 0.002, 2);
  CHECK(n1.A_m2 != n2.A_m2);
  CHECK(n1.A_m2 == standin_measured_curve(A0, Q_s, alpha, 60, 0.002, 1).A_m2);
  double ss = 0;
  for (std::size_t j = 0; j < 60; ++j) ss += std::pow((n1.A_m2[j] - c.A_m2[j]) / A0, 2);
  const double rms = std::sqrt(ss / 60);
  CHECK(rms > 0.001);  // 0.2 % noise: a chi distribution with 60 dof, far inside these bounds
  CHECK(rms < 0.003);
}

TEST_CASE("changing the seed changes a stand-in, keeping it the same size", "[generate]") {
  StandinRecipe r = load_recipe(kRecipe);
  const StandinExperiment a = build_standin(r, 0);
  r.seed += 1;
  const StandinExperiment b = build_standin(r, 0);
  CHECK(a.experiment.junctions.size() == b.experiment.junctions.size());
  CHECK(a.experiment.junctions.area_m2 != b.experiment.junctions.area_m2);
  CHECK(a.experiment.measured->A_m2 != b.experiment.measured->A_m2);
  CHECK(a.experiment.name == b.experiment.name);
}

TEST_CASE("contact-disc positions leave areas and measured curve unchanged and pass the overlap check",
          "[generate][positions]") {
  StandinRecipe r = load_recipe(kRecipe);
  const StandinExperiment plain = build_standin(r, 4);  // P4.00N
  r.contact_radius_m = 4.5e-3;
  const StandinExperiment placed = build_standin(r, 4);
  const JunctionPopulation& J = placed.experiment.junctions;
  CHECK(J.area_m2 == plain.experiment.junctions.area_m2);
  CHECK(placed.experiment.measured->A_m2 == plain.experiment.measured->A_m2);
  REQUIRE(J.x_m.size() == J.size());
  CHECK_FALSE(first_overlap(J).has_value());
  // Inside the Hertz radius at 4.00 N: R = 4.5 mm · (P / 4 N)^(1/3).
  const double R = 4.5e-3 * std::cbrt(placed.P / 4.0);
  double r_max = 0;
  for (std::size_t i = 0; i < J.size(); ++i) r_max = std::max(r_max, std::hypot(J.x_m[i], J.y_m[i]));
  CHECK(r_max < R);
  CHECK(r_max > 0.8 * R);  // the density reaches the edge
  CHECK_THAT(placed.experiment.description, Catch::Contains("contact disc of radius"));
}

TEST_CASE("regenerating the stand-ins reproduces the committed files byte for byte", "[generate]") {
  TempDir dir("standin");
  const StandinRecipe r = load_recipe(kRecipe);
  GenerateOptions opt;
  opt.out_dir = dir.path / "data" / "standin";
  opt.scenes_dir = dir.path / "scenes" / "paper";
  const auto xs = generate_standins(r, opt);
  REQUIRE(xs.size() == 6);

  std::size_t compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(opt.out_dir)) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = entry.path().lexically_relative(opt.out_dir);
    INFO("data/standin/" << rel.generic_string());
    const fs::path committed = kSource / "data" / "standin" / rel;
    REQUIRE(fs::exists(committed));
    CHECK(slurp(entry.path()) == slurp(committed));
    ++compared;
  }
  CHECK(compared == 6 * 4 + 1);  // experiment.yaml, junctions.csv, measured.csv, measured_Qt.csv; README.md
  for (const auto& x : xs) {
    const std::string name = x.experiment.name + ".yaml";
    INFO("scenes/paper/" << name);
    const fs::path committed = kSource / "scenes" / "paper" / name;
    REQUIRE(fs::exists(committed));
    CHECK(slurp(opt.scenes_dir / name) == slurp(committed));
  }
}

TEST_CASE("the committed stand-ins load and satisfy the §7 bookkeeping", "[generate]") {
  const StandinRecipe r = load_recipe(kRecipe);
  for (std::size_t i = 0; i < r.masses_kg.size(); ++i) {
    const double P = r.masses_kg[i] * r.gravity;
    const std::string name = standin_name(P);
    INFO(name);
    const Experiment e = load_experiment(kSource / "data" / "standin" / name / "experiment.yaml");
    CHECK(e.mass_kg == r.masses_kg[i]);
    CHECK_THAT(e.description, Catch::Contains("STAND-IN"));
    CHECK(e.junctions.size() == static_cast<std::size_t>(std::llround(300 * P)));
    REQUIRE(e.measured);
    CHECK(e.measured->Q_N.size() == 60);
    double A0 = 0;
    for (double a : e.junctions.area_m2) A0 += a;
    // Area drop of the stand-in measured curve at Q_s (last point), up to the 0.2 % noise.
    const double drop = 1.0 - e.measured->A_m2.back() / A0;
    const double target =
        0.15 + 0.10 * (P - r.masses_kg.front() * r.gravity) / ((r.masses_kg.back() - r.masses_kg.front()) * r.gravity);
    CHECK(std::abs(drop - target) < 0.01);
    // Scene of the paper on this stand-in loads too.
    const Scene s = load_scene(kSource / "scenes" / "paper" / (name + ".yaml"));
    CHECK(s.experiment.junctions.area_m2 == e.junctions.area_m2);
    CHECK(s.stop.time == r.scene_stop_time);  // long enough for the slowest peak (≈ 6 s)
    CHECK(s.output.every == 1e-3);
  }
}
