// Regression runs: tolerances from the tightened twin, comparison, and drift detection end to end.
#include <unistd.h>

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support_files.hpp"
#include "regress/regress.hpp"
#include "scene/load.hpp"

using namespace asperity;
namespace fs = std::filesystem;

TEST_CASE("regress: tolerance is 10x the tightening change, floored at 10x the solver tolerance", "[regress]") {
  RegressResult r;
  r.name = "x";
  r.solver_rel_floor = 1e-8;
  r.values = {{"Q_s", 2.0}, {"ss_drop", 0.5}, {"ss_cycles", 5}, {"ss_period", std::nan("")}};
  r.tight = {{"Q_s", 2.0 + 1e-6}, {"ss_drop", 0.5}, {"ss_cycles", 4}, {"ss_period", std::nan("")}};
  const Golden g = bless({r}, {});
  CHECK_THAT(g.entries.at("x").at("Q_s").tolerance, Catch::Matchers::WithinRel(1e-5, 1e-9));
  CHECK_THAT(g.entries.at("x").at("ss_drop").tolerance, Catch::Matchers::WithinRel(0.5e-8, 1e-12));
  CHECK(g.entries.at("x").at("ss_cycles").tolerance == 1.0);
  // Round trip through the golden file, then compare: inside passes, outside drifts, NaN = NaN.
  const fs::path f = asperity::testing::temp_path("asperity_test_golden", ".yaml");
  std::ofstream(f) << golden_to_yaml(g);
  const Golden back = load_golden(f);
  CHECK(back.entries.at("x").at("Q_s").value == 2.0);
  RegressResult now = r;
  now.values["Q_s"] = 2.0 + 0.9e-5;
  now.values["ss_drop"] = 0.5 + 1e-8;
  int drifted = 0;
  for (const auto& d : compare(back, {now})) {
    drifted += d.ok ? 0 : 1;
    if (d.observable == "ss_drop") CHECK_FALSE(d.ok);
    if (d.observable == "Q_s") CHECK(d.ok);
    if (d.observable == "ss_period") CHECK(d.ok);
  }
  CHECK(drifted == 1);
  fs::remove(f);
}

TEST_CASE("asperity regress passes on the committed golden results and catches an injected drift", "[regress][cli][heavy]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path work = asperity::testing::temp_path("asperity_test_regress");
  fs::remove_all(work);
  fs::create_directories(work);
  auto run = [&](const std::string& args) {
    const std::string cmd = "cd '" + src.string() + "' && '" + ASPERITY_BINARY + "' regress " + args + " >'" +
                            (work / "out.txt").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  CHECK(run("") == 0);
  // The same suite with η changed by 0.5 % in one entry must drift, naming that entry.
  std::ifstream in(src / "scenes/regression/suite.yaml");
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const std::string from = "../paper/P0.98N.yaml, set: [stop.cycles=5]";
  REQUIRE(text.find(from) != std::string::npos);
  text.replace(text.find(from), from.size(), "'" + (src / "scenes/paper/P0.98N.yaml").string() +
                                                 "', set: [stop.cycles=5, model.eta=100.5]");
  // Other scene paths are relative to the suite: keep the copy beside the original.
  const fs::path drift = src / "scenes/regression" / asperity::testing::temp_path(".drift_test_suite", ".yaml").filename();
  std::ofstream(drift) << text;
  const int rc = run("--suite '" + drift.string() + "'");
  fs::remove(drift);
  std::ifstream out(work / "out.txt");
  std::stringstream o;
  o << out.rdbuf();
  INFO("regress output: " << o.str());
  CHECK(rc == 1);
  CHECK(o.str().find("P0.98N_stick_slip") != std::string::npos);
  CHECK(o.str().find("DRIFT") != std::string::npos);
  CHECK(o.str().find("P6.40N_stick_slip") == std::string::npos);  // untouched entries still pass
  fs::remove_all(work);
}
