// src/scene/campaign_load: every bad campaign gives an InputError naming file, line and key.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "campaign/campaign_load.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using Catch::Matchers::Contains;

namespace {

const fs::path& kData = asperity::testing::kCampaignData;

fs::path temp_dir() { return asperity::testing::numbered_dir("asperity_campaign_in"); }

// A campaign file whose line 1 is the scene list; `body` starts at line 2.
fs::path campaign_file(const std::string& body) {
  const fs::path p = temp_dir() / "c.yaml";
  std::ofstream(p) << "scenes: [" << (kData / "tiny_scene.yaml").string() << "]\n" << body;
  return p;
}

struct Expect {
  int line;
  std::string key, message;
};

void check_error(const std::string& body, const Expect& e) {
  const fs::path p = campaign_file(body);
  try {
    load_campaign(p);
    FAIL("no error for:\n" << body);
  } catch (const io::InputError& err) {
    INFO(err.what());
    CHECK(err.file == p.lexically_normal().string());
    CHECK(err.line == e.line);
    CHECK_THAT(err.key, Contains(e.key));
    CHECK_THAT(err.message, Contains(e.message));
  }
}

}  // namespace

TEST_CASE("a valid campaign loads with its grids axes and set", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  CHECK(c.name == "tiny");
  CHECK(c.scenes.size() == 1);
  REQUIRE(c.grids.size() == 2);
  CHECK(c.grids[0].size() == 9);
  CHECK(c.grids[1].combine == Combine::zip);
  CHECK(c.size() == 11);
  // Every point builds a scene with the point's values.
  const CampaignScenes scenes(c);
  const Scene s = scenes.scene(point_at(c, 10));
  CHECK(s.experiment.mass_kg == 0.1);
  CHECK(s.model.alpha_b == 1.2e-15);
  CHECK(s.stop.time == 0.3);
  CHECK(CampaignScenes::value_text(s, "model.eta") == "100");
  CHECK(CampaignScenes::value_text(s, "experiment").empty());
}

TEST_CASE("an experiment axis takes paths relative to the campaign file", "[campaign]") {
  const fs::path d = temp_dir();
  fs::create_directories(d / "exps" / "a");
  fs::copy(fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "scene" / "exp_small", d / "exps" / "a",
           fs::copy_options::recursive);
  std::ofstream(d / "c.yaml") << "scenes: [" << (kData / "tiny_scene.yaml").string() << "]\n"
                              << "axes: {experiment: [exps/a/experiment.yaml]}\n";
  const Campaign c = load_campaign(d / "c.yaml");
  const Scene s = CampaignScenes(c).scene(point_at(c, 0));
  CHECK(fs::equivalent(s.experiment.file, d / "exps" / "a" / "experiment.yaml"));
}

TEST_CASE("bad campaign structure is reported at its line", "[campaign]") {
  check_error("axess: {model.eta: [1]}\n", {2, "axess", "unknown key"});
  check_error("axes: {model.eta: []}\n", {2, "model.eta", "empty axis"});
  check_error("axes:\n  model.eta: {linspace: [0, 1, 0]}\n", {3, "model.eta", "empty axis"});
  check_error("axes: {}\n", {2, "axes", "empty"});
  check_error("axes:\n  model.eta: {steps: [0, 1, 3]}\n", {3, "steps", "unknown key"});
  check_error("axes:\n  model.eta: 5\n", {3, "model.eta", "expected a list"});
  check_error("combine: zip\naxes:\n  model.eta: [1, 2]\n  model.epsilon: [0.5, 0.6, 0.7]\n",
              {5, "model.epsilon", "equal length"});
  check_error("combine: diagonal\naxes: {model.eta: [1]}\n", {2, "combine", "unknown value"});
  check_error("grids:\n  - {name: a, combin: zip, axes: {model.eta: [1]}}\n", {3, "combin", "unknown key"});
  check_error("axes: {model.eta: [1]}\ngrids: [{axes: {model.eta: [1]}}]\n", {3, "grids", "either"});
  check_error("axes:\n  model.alpha_b: {logspace: [0, 1e-15, 3]}\n", {3, "logspace", "non-zero"});
  check_error("time_limit: 0\n", {2, "time_limit", "must be > 0"});
  check_error("time_limit: 10 min\n", {2, "time_limit", "SI units"});
}

TEST_CASE("bad axis values are reported at their line", "[campaign]") {
  check_error("axes:\n  model.eta:\n    - 10\n    - fast\n", {5, "model.eta", "mixed numbers and texts"});
  check_error("axes:\n  solver.tolerance: [1e-9, 1e-6 s]\n", {3, "solver.tolerance", "SI units"});
  check_error("axes:\n  model.eta: [10, .nan]\n", {3, "model.eta", "finite"});
  check_error("axes:\n  model.eta: [10, 20, 10]\n", {3, "model.eta", "listed twice"});
}

TEST_CASE("axes and set entries the scene rejects are reported at the campaign line", "[campaign]") {
  check_error("axes:\n  model.etaa: [1, 2]\n", {3, "model.etaa", "unknown key"});
  check_error("axes:\n  model.epsilon: [0.5, 1.5]\n", {3, "model.epsilon", "in (0, 1]"});
  check_error("axes:\n  model.epsilon: {linspace: [0.5, 1.2, 4]}\n", {3, "model.epsilon", "in (0, 1]"});
  check_error("axes:\n  solver.method: [event, fastest]\n", {3, "solver.method", "unknown value"});
  check_error("axes:\n  experiment: [nowhere/experiment.yaml]\n", {3, "experiment", "not found"});
  check_error("axes:\n  experiment.mass: [0.1, -1]\n", {3, "experiment.mass", "> 0"});
  check_error("set:\n  stop.time: 1\n  stop.cylces: 5\n", {4, "set.stop.cylces", "unknown key"});
  check_error("set: {model.eta: 10}\naxes: {model.eta: [1, 2]}\n", {3, "model.eta", "also fixed by set"});
}

TEST_CASE("missing or bad scene lists are reported", "[campaign]") {
  const fs::path d = temp_dir();
  std::ofstream(d / "a.yaml") << "axes: {model.eta: [1]}\n";
  CHECK_THROWS_WITH(load_campaign(d / "a.yaml"), Contains("scenes: missing required key"));
  std::ofstream(d / "b.yaml") << "name: b\nscenes: [nothere.yaml]\n";
  try {
    load_campaign(d / "b.yaml");
    FAIL("no error");
  } catch (const io::InputError& e) {
    CHECK(e.line == 2);
    CHECK_THAT(e.message, Contains("scene file not found"));
  }
  std::ofstream(d / "c.yaml") << "name: a/b\nscenes: [" << (kData / "tiny_scene.yaml").string() << "]\n";
  CHECK_THROWS_WITH(load_campaign(d / "c.yaml"), Contains("c.yaml:1: name: must be a plain folder name"));
  CHECK_THROWS_WITH(load_campaign(d / "none.yaml"), Contains("file not found"));
}
