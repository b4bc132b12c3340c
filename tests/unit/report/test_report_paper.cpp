// The paper reproduction: loading-branch time lookup and `asperity reproduce` end to end.
#include <unistd.h>

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "observe/simulate.hpp"
#include "report/paper_figures.hpp"
#include "scene/load.hpp"
#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;

TEST_CASE("loading_time_at inverts a linear loading branch and is NaN beyond it", "[report]") {
  std::vector<Sample> s;
  for (int i = 0; i <= 10; ++i) s.push_back(Sample{0.1 * i, 0, 0, 2.0 * 0.1 * i, 1.0, 0, 0});
  CHECK(loading_time_at(s, 0.0) == 0.0);
  CHECK_THAT(loading_time_at(s, 1.23), Catch::Matchers::WithinRel(0.615, 1e-12));
  CHECK(std::isnan(loading_time_at(s, 2.5)));
}

TEST_CASE("asperity reproduce: table rows equal single runs, figures written", "[report][cli][heavy]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path work = asperity::testing::temp_path("asperity_test_reproduce");
  fs::remove_all(work);
  fs::create_directories(work);
  const fs::path s1 = src / "scenes/paper/P0.98N.yaml", s2 = src / "scenes/paper/P1.52N.yaml";
  const std::string cmd = std::string("'") + ASPERITY_BINARY + "' reproduce '" + s2.string() + "' '" + s1.string() +
                          "' --out '" + (work / "out").string() + "' --set stop.at_first_peak=true --quiet 2>'" +
                          (work / "err").string() + "'";
  const int rc = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(rc));
  REQUIRE(WEXITSTATUS(rc) == 0);
  CHECK(fs::file_size(work / "out/fig3_Q_A_t.png") > 10000);
  CHECK(fs::file_size(work / "out/fig4_A_Q.png") > 10000);
  CHECK(fs::exists(work / "out/P0.98N/summary.yaml"));
  // Second method: the same scene run in process. Rows come smallest load first.
  std::ifstream t(work / "out/table.csv");
  std::string header, row;
  std::getline(t, header);
  std::getline(t, row);
  const RunResult r = simulate(load_scene(s1, {"stop.at_first_peak=true"}));
  std::istringstream in(row);
  std::string name, N, A0, dt, Qs;
  std::getline(in, name, ',');
  std::getline(in, N, ',');
  std::getline(in, A0, ',');
  std::getline(in, dt, ',');
  std::getline(in, Qs, ',');
  CHECK(name == "P0.98N");
  CHECK(std::stod(N) == static_cast<double>(r.obs.N));
  CHECK(std::stod(Qs) == r.obs.Q_s);  // same deterministic run, %.17g round trip
  fs::remove_all(work);
}
