// Study files (studies/study_load.hpp): the committed ones read as the studies ran before they
// had files, and relative paths are read against the study file's folder.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>
#include <variant>

#include "io/input_error.hpp"
#include "studies/study_load.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using asperity::testing::fresh_dir;
using asperity::testing::write_text;

TEST_CASE("study files: the committed studies name the repository's inputs and outputs", "[studies][study_load]") {
  const fs::path src = ASPERITY_SOURCE_DIR;
  const StudySpec in = load_study(src / "studies/interactions.yaml");
  REQUIRE(in.kind == "interactions");
  const auto& i = std::get<InteractionStudyOptions>(in.options);
  REQUIRE(i.scenes.size() == 6);
  CHECK(i.scenes.front() == (src / "scenes/paper/P0.98N.yaml").lexically_normal());
  CHECK(i.scenes.back() == (src / "scenes/paper/P6.40N.yaml").lexically_normal());
  CHECK(i.fit_independent == (src / "results/fits/paper_alpha_b/fit.yaml").lexically_normal());
  CHECK(i.joint_interacting.size() == 5);
  CHECK(i.joint_interacting.back() == (src / "results/fits/joint_interacting_P6.40N/fit.yaml").lexically_normal());
  CHECK(i.recovery_matrix == (src / "results/recovery/matrix.csv").lexically_normal());
  CHECK(i.out == (src / "results/interactions").lexically_normal());
  CHECK(i.spread_experiment == "P4.00N");
  const StudySpec rec = load_study(src / "studies/recovery.yaml");
  const auto& r = std::get<RecoveryMatrixOptions>(rec.options);
  CHECK(r.recipes.size() == 4);
  REQUIRE(r.models.size() == 2);
  CHECK(r.models[1].label == "interacting");
  CHECK(r.models[1].interactions == "elastic");
  CHECK(r.models[1].fit_template == (src / "examples/recovery/fit_interacting.yaml").lexically_normal());
  const StudySpec con = load_study(src / "studies/continuum.yaml");
  const auto& c = std::get<ContinuumStudyOptions>(con.options);
  CHECK(c.loads_N.size() == 9);
  CHECK(c.loads_N.front() == 0.02);
  CHECK(c.points == 32);
  CHECK(c.threads == 1);
}

TEST_CASE("study files: a path relative to the file, run from elsewhere, names the same file",
          "[studies][study_load]") {
  const fs::path dir = fresh_dir("asperity-study-load");
  write_text(dir / "a" / "recipe.yaml", "# not read by the loader\n");
  const fs::path study = write_text(dir / "a" / "s.yaml",
                                    "study: continuum\nout: ../out\nrecipe: recipe.yaml\nloads_N: [1]\n"
                                    "points: 5\n");
  const StudySpec spec = load_study(study);
  const auto& c = std::get<ContinuumStudyOptions>(spec.options);
  CHECK(c.recipe == dir / "a" / "recipe.yaml");
  CHECK(c.out == dir / "out");
  CHECK(c.points == 5);
  // Two listed files that are one file are refused at the second.
  write_text(dir / "a" / "r.yaml", "# a recipe\n");
  const fs::path twice = write_text(
      dir / "a" / "t.yaml",
      "study: recovery\nout: o\nrecipes: [r.yaml, ./r.yaml]\nmodels:\n"
      "  - {label: a, interactions: none, fit: r.yaml}\n  - {label: b, interactions: elastic, fit: r.yaml}\n");
  try {
    load_study(twice);
    FAIL("no error");
  } catch (const io::InputError& e) {
    CHECK(e.line == 3);
    CHECK(e.key == "recipes[1]");
    CHECK(e.message == "'./r.yaml' listed twice");
  }
  fs::remove_all(dir);
}
