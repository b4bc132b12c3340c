// scene/scene_keys (plausible ranges) through the loader: a number allowed but far from any real
// experiment's, as a unit slip gives it, is warned about once, naming where it came from; no
// committed scene or experiment file is.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "io/warnings.hpp"
#include "scene/load.hpp"
#include "scene/scene_keys.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;

namespace {

const fs::path kSource = fs::path(ASPERITY_SOURCE_DIR);
const fs::path kScene = kSource / "tests" / "data" / "scene" / "small_scene.yaml";

// The warnings given while it lives (each test starts with none said).
struct CapturedWarnings {
  std::vector<std::string> texts;
  io::WarningSink previous;
  CapturedWarnings() {
    previous = io::set_warning_sink([this](const std::string& t) { texts.push_back(t); });
  }
  ~CapturedWarnings() { io::set_warning_sink(std::move(previous)); }
};

}  // namespace

TEST_CASE("plausible ranges: the unit slip is named, the paper's values pass", "[scene][plausible]") {
  const SceneKey& E = *find_scene_key("experiment.E");
  const SceneKey& mass = *find_scene_key("experiment.mass");
  CHECK(implausible_message(E, 1.6) ==
        "experiment.E = 1.6 Pa is far below an elastomer's 1e+05 to 1e+08 Pa; was it meant in MPa (1.6e+06 Pa)?");
  CHECK(implausible_message(mass, 408) ==
        "experiment.mass = 408 kg is far above a slider's 0.001 to 10 kg; was it meant in g (0.408 kg)?");
  // Of two units that land in range, the one nearer the paper's value: 100 meant in um/s, not mm/s.
  CHECK_THAT(implausible_message(*find_scene_key("experiment.v"), 100),
             Catch::Matchers::EndsWith("um/s (0.0001 m/s)?"));
  // No unit explains it: said without a guess.
  CHECK(implausible_message(E, 1e12) == "experiment.E = 1e+12 Pa is far above an elastomer's 1e+05 to 1e+08 Pa");
  CHECK(implausible_message(*find_scene_key("model.epsilon"), 0.01) ==
        "model.epsilon = 0.01 is far below a dynamic-to-static friction ratio's 0.1 to 1");
  // The paper's values (docs/model.md#2-parameter-values-the-papers) and the model's defaults.
  CHECK(implausible_message(E, 1.6e6).empty());
  for (const double m : {0.1, 0.155, 0.652}) CHECK(implausible_message(mass, m).empty());
  for (const SceneKey& k : scene_keys()) {
    INFO(k.name);
    if (k.kind != KeyKind::number || std::isnan(k.default_value)) continue;
    CHECK(implausible_message(k, k.default_value).empty());
  }
}

TEST_CASE("plausible ranges: one warning from the loader for --set and for file values", "[scene][plausible]") {
  SECTION("--set experiment.E=1.6: named by the --set, run anyway") {
    CapturedWarnings w;
    const Scene s = load_scene(kScene, {"experiment.E=1.6"});
    CHECK(s.experiment.E == 1.6);
    REQUIRE(w.texts.size() == 1);
    CHECK(w.texts[0] ==
          "--set experiment.E=1.6: experiment.E = 1.6 Pa is far below an elastomer's 1e+05 to 1e+08 Pa; "
          "was it meant in MPa (1.6e+06 Pa)?");
  }
  SECTION("--set experiment.mass=408 (grams)") {
    CapturedWarnings w;
    load_scene(kScene, {"experiment.mass=408"});
    REQUIRE(w.texts.size() == 1);
    CHECK_THAT(w.texts[0],
               Catch::Matchers::StartsWith("--set experiment.mass=408: experiment.mass = 408 kg is far above"));
    CHECK_THAT(w.texts[0], Catch::Matchers::EndsWith("was it meant in g (0.408 kg)?"));
  }
  SECTION("a scene file's value: FILE:LINE") {
    const fs::path dir = testing::fresh_dir("plausible-scene");
    const fs::path scene = testing::write_text(
        dir / "scene.yaml",
        "experiment:\n  file: " + (kScene.parent_path() / "exp_small" / "experiment.yaml").string() +
            "\n  mass: 408\nmodel: {eta: 50}\n");
    CapturedWarnings w;
    load_scene(scene);
    REQUIRE(w.texts.size() == 1);
    CHECK_THAT(w.texts[0],
               Catch::Matchers::StartsWith(scene.lexically_normal().string() + ":3: experiment.mass = 408 kg"));
    fs::remove_all(dir);
  }
  SECTION("an experiment file's value: its FILE:LINE") {
    const fs::path dir = testing::fresh_dir("plausible-experiment");
    fs::copy(kScene.parent_path() / "exp_small", dir / "exp", fs::copy_options::recursive);
    std::string text = testing::slurp(dir / "exp" / "experiment.yaml");
    text.replace(text.find("E: 1.6e6"), 8, "E: 1.6  ");
    testing::write_text(dir / "exp" / "experiment.yaml", text);
    testing::write_text(dir / "scene.yaml", "experiment: exp/experiment.yaml\n");
    CapturedWarnings w;
    load_scene(dir / "scene.yaml");
    REQUIRE(w.texts.size() == 1);
    CHECK_THAT(w.texts[0], Catch::Matchers::StartsWith((dir / "exp" / "experiment.yaml").lexically_normal().string() +
                                                       ":7: experiment.E = 1.6 Pa"));
    fs::remove_all(dir);
  }
  SECTION("a scene refused after the warning says its error alone") {
    CapturedWarnings w;
    CHECK_THROWS_AS(load_scene(kScene, {"experiment.E=1.6", "model.epsilon=1.5"}), io::InputError);
    CHECK(w.texts.empty());
    load_scene(kScene, {"experiment.E=1.6"});
    CHECK(w.texts.size() == 1);
  }
  SECTION("each text once; none for plausible values") {
    CapturedWarnings w;
    load_scene(kScene, {"experiment.E=1.6"});
    load_scene(kScene, {"experiment.E=1.6"});
    load_scene(kScene, {"experiment.E=1.7e6", "model.eta=200", "experiment.mass=0.408"});
    CHECK(w.texts.size() == 1);
  }
}

TEST_CASE("plausible ranges: every committed scene and experiment file loads without a warning", "[scene][plausible]") {
  CapturedWarnings w;
  int scenes = 0, experiments = 0;
  for (const char* top : {"scenes", "examples", "data"})
    for (const auto& e : fs::recursive_directory_iterator(kSource / top)) {
      if (e.path().extension() != ".yaml") continue;
      const YAML::Node tree = load_scene_tree(e.path());
      if (!tree.IsMap()) continue;
      INFO(e.path().string());
      // A scene names its experiment; an experiment file holds its junctions (fits, campaigns,
      // recipes and suites hold neither).
      if (tree["experiment"] && !tree["experiments"]) {
        load_scene(e.path());
        ++scenes;
      } else if (tree["junctions"] && tree["mass"]) {
        load_experiment(e.path());
        ++experiments;
      }
      CHECK(w.texts.empty());
      w.texts.clear();
    }
  // The paper's six and the regression, topography and recovery scenes; the stand-ins' experiments.
  CHECK(scenes >= 10);
  CHECK(experiments >= 9);
}
