// Scene keys model.interactions / model.interaction_cutoff: loaded, written only when on,
// and refused with one line when the junctions cannot interact (no positions, overlap) or the
// solver cannot run them.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "io/input_error.hpp"
#include "scene/load.hpp"
#include "scene/validate.hpp"
#include "solve/core/problem.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;
using Catch::Contains;

namespace {

const fs::path kExp = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "scene" / "exp_small";

// An experiment folder with the fixture's values and the given junctions CSV text.
fs::path experiment_with(const fs::path& dir, const std::string& junctions_csv) {
  fs::create_directories(dir);
  write_text(dir / "experiment.yaml", slurp(kExp / "experiment.yaml"));
  write_text(dir / "measured.csv", slurp(kExp / "measured.csv"));
  write_text(dir / "junctions.csv", junctions_csv);
  return dir / "experiment.yaml";
}

std::string error_of(const fs::path& scene, const std::vector<std::string>& sets = {}) {
  try {
    load_scene(scene, sets);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("interaction keys load, round-trip, and stay out of scenes that do not use them", "[scene][interacting]") {
  const fs::path dir = temp_path("scene_interactions");
  fs::remove_all(dir);
  experiment_with(dir / "exp", "area_m2,x_m,y_m\n1e-8,0,0\n2e-8,3e-4,0\n1.5e-8,0,4e-4\n");
  const fs::path scene = write_text(dir / "s.yaml",
                                    "experiment: exp/experiment.yaml\n"
                                    "model: {interactions: elastic, interaction_cutoff: 2e-4}\n"
                                    "solver: {method: reference, Ct: 200}\n");
  const Scene s = load_scene(scene);
  CHECK(s.model.interactions == Interactions::elastic);
  CHECK(s.model.interaction_cutoff == 2e-4);
  const std::string text = scene_to_yaml(s);
  CHECK_THAT(text, Contains("  interactions: elastic\n") && Contains("  interaction_cutoff: 2e-04\n"));
  const fs::path again = write_text(dir / "again.yaml", text);
  CHECK(scene_to_yaml(load_scene(again)) == text);
  // Off (the default): not written, so the text and a store's point hashes are as before.
  const Scene off = load_scene(scene, {"model.interactions=none"});
  CHECK(scene_to_yaml(off).find("  interaction") == std::string::npos);
  // A negative cut-off is out of range.
  CHECK_THAT(error_of(scene, {"model.interaction_cutoff=-1"}),
             Contains("model.interaction_cutoff") && Contains(">= 0"));
  fs::remove_all(dir);
}

TEST_CASE("interactions are refused with one line for overlapping or unplaced junctions", "[scene][interacting]") {
  const fs::path dir = temp_path("scene_interactions_bad");
  fs::remove_all(dir);
  // The fixture's junctions 3 (at 0, 0, radius 69 µm) and 5 (at 100 µm, radius 40 µm) overlap.
  fs::create_directories(dir);
  const fs::path fixture =
      write_text(dir / "fixture.yaml", "experiment: " + (kExp / "experiment.yaml").string() +
                                           "\nmodel: {interactions: elastic}\nsolver: {method: reference}\n");
  CHECK_THAT(error_of(fixture), Contains("junctions.csv") && Contains("junctions 3 and 5 overlap"));
  // No positions.
  experiment_with(dir / "bare", "area_m2\n1e-8\n2e-8\n");
  const fs::path bare =
      write_text(dir / "bare.yaml",
                 "experiment: bare/experiment.yaml\nmodel: {interactions: elastic}\nsolver: {method: reference}\n");
  CHECK_THAT(error_of(bare), Contains("bare.yaml:2") && Contains("model.interactions") && Contains("no x_m and y_m"));
  // Separate, placed junctions load with either solver (the event solver is the default).
  experiment_with(dir / "ok", "area_m2,x_m,y_m\n1e-8,0,0\n2e-8,3e-4,0\n");
  const fs::path event =
      write_text(dir / "event.yaml", "experiment: ok/experiment.yaml\nmodel: {interactions: elastic}\n");
  CHECK(error_of(event).empty());
  fs::remove_all(dir);
}

TEST_CASE("interactions are refused with one line beyond 20,000 junctions (the dense matrix's memory)",
          "[scene][interacting]") {
  // N junctions of 1e-10 m² (radius 5.6 µm) on a 1 mm lattice: none overlap.
  const auto lattice = [](std::size_t n) {
    std::string csv = "area_m2,x_m,y_m\n";
    for (std::size_t i = 0; i < n; ++i)
      csv += "1e-10," + std::to_string(1e-3 * static_cast<double>(i % 150)) + "," +
             std::to_string(1e-3 * static_cast<double>(i / 150)) + "\n";
    return csv;
  };
  const fs::path dir = temp_path("scene_interactions_many");
  fs::remove_all(dir);
  experiment_with(dir / "most", lattice(20000));
  experiment_with(dir / "over", lattice(20001));
  const fs::path most =
      write_text(dir / "most.yaml", "experiment: most/experiment.yaml\nmodel: {interactions: elastic}\n");
  const fs::path over =
      write_text(dir / "over.yaml", "experiment: over/experiment.yaml\nmodel: {interactions: elastic}\n");
  CHECK(error_of(most).empty());
  CHECK_THAT(error_of(over), Contains("over.yaml:2") && Contains("model.interactions") && Contains("N = 20001") &&
                                 Contains("more than 20000"));
  fs::remove_all(dir);
}

TEST_CASE("first_overlap finds the overlapping pair among many and none in a clean lattice", "[scene][interacting]") {
  JunctionPopulation J;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      J.area_m2.push_back(M_PI * 0.49e-4 * 0.49e-4);  // radius 49 µm on a 100 µm lattice
      J.x_m.push_back(i * 1e-4);
      J.y_m.push_back(j * 1e-4);
    }
  CHECK_FALSE(first_overlap(J).has_value());
  J.x_m[700] += 0.03e-4;  // now 97 µm from its neighbour at +x: radii sum 98 µm
  const auto pair = first_overlap(J);
  REQUIRE(pair.has_value());
  CHECK(pair->first == 700);
  CHECK(pair->second == 740);
}

TEST_CASE("model.position_scale multiplies the centres the run uses and is checked for overlap there",
          "[scene][interacting]") {
  const fs::path dir = temp_path("scene_position_scale");
  fs::remove_all(dir);
  // Two junctions of radius 56 µm and 80 µm, centres 300 µm apart: they touch at scale 0.453.
  experiment_with(dir / "ok", "area_m2,x_m,y_m\n1e-8,1e-4,0\n2e-8,4e-4,0\n");
  const fs::path scene = write_text(dir / "s.yaml", "experiment: ok/experiment.yaml\nmodel: {interactions: elastic}\n");
  const Scene s = load_scene(scene, {"model.position_scale=2.5"});
  const Problem p = make_problem(s);
  REQUIRE(p.x.size() == 2);
  CHECK(p.x[0] == 2.5e-4);
  CHECK(p.x[1] == 1e-3);
  CHECK(s.experiment.junctions.x_m[1] == 4e-4);  // the population itself is untouched
  // Written when interactions are on (the default scale is not written without them).
  CHECK(scene_to_yaml(s).find("position_scale: 2.5") != std::string::npos);
  CHECK(scene_to_yaml(load_scene(scene, {"model.interactions=none"})).find("  position_scale:") == std::string::npos);
  // 0.5 keeps them apart (150 µm > 56 + 80 µm); 0.4 makes them overlap: one line naming the key.
  CHECK(error_of(scene, {"model.position_scale=0.5"}).empty());
  CHECK_THAT(error_of(scene, {"model.position_scale=0.4"}),
             Contains("model.position_scale") && Contains("junctions 1 and 2") && Contains("overlap at scale 0.4"));
  CHECK_THAT(error_of(scene, {"model.position_scale=0"}), Contains("model.position_scale") && Contains("(0, 1e6]"));
  fs::remove_all(dir);
}
