// Synthetic experiments (generate/synthetic.hpp): one run gives both curves, labelled SYNTHETIC,
// readable by the experiment loader, same recipe → same bytes; the recipe reader's errors.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "generate/synthetic.hpp"
#include "generate/synthetic_recipe.hpp"
#include "io/input_error.hpp"
#include "scene/load.hpp"
#include "synthetic_support.hpp"

using namespace asperity;
using namespace asperity::testing;
namespace fs = std::filesystem;

namespace {

const char* kFiles[] = {"experiment.yaml", "junctions.csv", "measured.csv",
                        "measured_Qt.csv", "scene.yaml",    "README.md"};

// The InputError a recipe text raises ("" when it loads).
std::string recipe_error(const fs::path& dir, const std::string& text) {
  const fs::path f = write_text(dir / "bad.yaml", text);
  try {
    load_synthetic_recipe(f);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a synthetic experiment holds A(Q) and Q(t) from one run, labelled, in the loaders' format, same bytes twice",
          "[generate][synthetic]") {
  const fs::path dir = fresh_dir("asperity-synthetic");
  write_base_scene(dir, 0.1, 40);
  const SyntheticTruth truth{0.8e-15, 0.85, 120, "none"};
  const fs::path recipe_file =
      write_text(dir / "recipe.yaml", synthetic_recipe_text("base/scene.yaml", truth, 0.002, 7, 1.0));
  const SyntheticRecipe r = load_synthetic_recipe(recipe_file);
  CHECK(r.scene.model.alpha_b == truth.alpha_b);
  CHECK(r.scene.model.epsilon == truth.epsilon);
  CHECK(r.scene.model.eta == truth.eta);
  CHECK(r.name == "base-synthetic");

  const SyntheticExperiment x = build_synthetic(r);
  REQUIRE(x.model.peak_found);
  REQUIRE(x.experiment.measured);
  CHECK(x.experiment.measured->Q_N.size() == 40);
  CHECK(x.experiment.measured->Q_N.back() == x.model.Q_s);
  CHECK(x.force.t_s.size() == 201);  // 0, 0.005, ..., 1.0
  CHECK(x.force_scale >= x.model.Q_s);
  write_synthetic_experiment(r, x, dir / "a");
  write_synthetic_experiment(r, build_synthetic(r), dir / "b");
  for (const char* f : kFiles) {
    INFO(f);
    CHECK(slurp(dir / "a" / f) == slurp(dir / "b" / f));
  }
  // Labelled wherever the data go, with the truth that made them.
  const std::string label = "SYNTHETIC, NOT A MEASUREMENT";
  for (const char* f : kFiles) {
    INFO(f);
    CHECK(slurp(dir / "a" / f).find(label) != std::string::npos);
  }
  CHECK(slurp(dir / "a" / "README.md").find("alpha_b = 8e-16 m^5/N^2, epsilon = 0.85, eta = 120 1/s") !=
        std::string::npos);

  // The written scene reproduces the run at the truth, and its experiment reads back.
  const Scene s = load_scene(dir / "a" / "scene.yaml");
  CHECK(s.model.alpha_b == truth.alpha_b);
  CHECK(s.model.eta == truth.eta);
  CHECK(s.experiment.name == "base-synthetic");
  REQUIRE(s.experiment.measured);
  CHECK(s.experiment.measured->A_m2 == x.experiment.measured->A_m2);
  CHECK(s.experiment.junctions.area_m2 == r.scene.experiment.junctions.area_m2);

  // Another seed, other noise; no noise, the model's own curves.
  const SyntheticRecipe other = load_synthetic_recipe(
      write_text(dir / "r2.yaml", synthetic_recipe_text("base/scene.yaml", truth, 0.002, 8, 1.0)));
  CHECK(build_synthetic(other).experiment.measured->A_m2 != x.experiment.measured->A_m2);
  const SyntheticRecipe exact =
      load_synthetic_recipe(write_text(dir / "r3.yaml", synthetic_recipe_text("base/scene.yaml", truth, 0, 7, 1.0)));
  const SyntheticExperiment xe = build_synthetic(exact);
  CHECK(xe.experiment.measured->A_m2.front() == xe.model.A0);  // Q = 0: no junction has moved
  fs::remove_all(dir);
}

TEST_CASE("the synthetic recipe reader refuses unknown keys, keys it does not own and bad values at their line",
          "[generate][synthetic]") {
  const fs::path dir = fresh_dir("asperity-synthetic-bad");
  write_base_scene(dir, 0.1, 10);
  const std::string good = synthetic_recipe_text("base/scene.yaml", SyntheticTruth{}, 0.002, 1, 1.0);
  CHECK(recipe_error(dir, good).empty());
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    t.replace(t.find(from), from.size(), to);
    return recipe_error(dir, t);
  };
  CHECK_THAT(recipe_error(dir, good + "  colour: red\n"),
             Catch::Contains("bad.yaml:12: synthetic.colour: unknown key"));
  CHECK_THAT(replaced("    model.eta: 100\n", "    stop.time: 5\n"),
             Catch::Contains("bad.yaml:6: synthetic.set.stop.time: only model.* and solver.* keys may be set"));
  CHECK_THAT(replaced("model.eta: 100", "model.eta: -1"), Catch::Contains("bad.yaml:6: synthetic.set.model.eta:"));
  CHECK_THAT(replaced("model.interactions: none", "model.interactions: springs"),
             Catch::Contains("bad.yaml:7: synthetic.set.model.interactions:"));
  CHECK_THAT(replaced("model.eta: 100", "model.etta: 100"), Catch::Contains("bad.yaml:6: synthetic.set.model.etta:"));
  CHECK_THAT(replaced("noise: {area: 0.002", "noise: {area: 0.5"),
             Catch::Contains("bad.yaml:9: synthetic.noise.area: must be in [0, 0.1)"));
  CHECK_THAT(replaced("points: 40", "points: 1"), Catch::Contains("synthetic.measured.points: must be at least 2"));
  CHECK_THAT(replaced("end: 1", "end: 0.005"),
             Catch::Contains("synthetic.measured_force.end: must be at least two samples"));
  CHECK_THAT(replaced("scene: base/scene.yaml", "scene: nowhere.yaml"),
             Catch::Contains("bad.yaml:2: synthetic.scene: scene file not found"));
  CHECK_THAT(replaced("  seed: 1\n", ""), Catch::Contains("synthetic.seed"));
  // A window that ends before the peak is the recipe's to fix.
  const fs::path short_window =
      write_text(dir / "short.yaml", synthetic_recipe_text("base/scene.yaml", SyntheticTruth{}, 0.002, 1, 0.05));
  CHECK_THROWS_WITH(build_synthetic(load_synthetic_recipe(short_window)),
                    Catch::Contains("short.yaml:11: synthetic.measured_force.end: the run showed no confirmed peak"));
  fs::remove_all(dir);
}
