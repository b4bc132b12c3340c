// `asperity bench`: bad input is reported with the file named; accuracy writes its CSV.
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support.hpp"

namespace fs = std::filesystem;

namespace {

using asperity::testing::slurp;

int run_cli(const std::string& args, const fs::path& work, std::string* err) {
  const std::string cmd = "cd '" + work.string() + "' && '" + ASPERITY_BINARY + "' " + args +
                          " >stdout.txt 2>stderr.txt";
  const int rc = std::system(cmd.c_str());
  *err = slurp(work / "stderr.txt");
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string c; std::getline(in, c, ',');) out.push_back(c);
  return out;
}

}  // namespace

TEST_CASE("bench names a missing scene file and writes nothing", "[bench][cli]") {
  const fs::path w = fs::temp_directory_path() / ("asperity-bench-cli-" + std::to_string(::getpid()));
  fs::remove_all(w);
  fs::create_directories(w);
  std::string err;
  CHECK(run_cli("bench tradeoff --scene no_such_scene.yaml --out out", w, &err) == 2);
  CHECK_THAT(err, Catch::Matchers::Contains("no_such_scene.yaml"));
  CHECK_THAT(err, Catch::Matchers::Contains("not found"));
  CHECK(!fs::exists(w / "out"));
  CHECK(run_cli("bench accuracy --scenes-dir no_such_folder --out out", w, &err) == 2);
  CHECK_THAT(err, Catch::Matchers::Contains("no_such_folder"));
  fs::remove_all(w);
}

TEST_CASE("bench accuracy writes one row per scene and tolerance against the converged run", "[bench][cli]") {
  const fs::path w = fs::temp_directory_path() / ("asperity-bench-acc-" + std::to_string(::getpid()));
  fs::remove_all(w);
  fs::create_directories(w);
  const std::string scene = std::string(ASPERITY_SOURCE_DIR) + "/scenes/paper/P0.98N.yaml";
  std::string err;
  REQUIRE(run_cli("bench accuracy --scene '" + scene + "' --tolerance 1e-6 1e-9 --out out", w, &err) == 0);
  std::istringstream csv(slurp(w / "out" / "accuracy.csv"));
  std::string header, line;
  REQUIRE(std::getline(csv, header));
  const auto cols = split(header);
  auto col = [&](const std::string& name) {
    for (std::size_t i = 0; i < cols.size(); ++i)
      if (cols[i] == name) return i;
    FAIL("no column " << name);
    return std::size_t{0};
  };
  int rows = 0;
  while (std::getline(csv, line)) {
    const auto f = split(line);
    REQUIRE(f.size() == cols.size());
    CHECK(f[col("experiment")] == "P0.98N");
    // The error column is |value − converged| / converged of the other two columns.
    const double v = std::stod(f[col("value_Q_s")]), c = std::stod(f[col("converged_Q_s")]);
    CHECK(std::abs(std::stod(f[col("relerr_Q_s")]) - std::abs(v - c) / c) < 1e-3 * std::abs(v - c) / c + 1e-15);
    // A few times the errors measured on P0.98N: 5.7e-9 at tolerance 1e-6, 2.0e-11 at 1e-9.
    const double tol = std::stod(f[col("tolerance")]);
    CHECK(std::abs(v - c) / c < (tol > 1e-7 ? 3e-8 : 1e-10));
    CHECK(f[col("within_targets")] == "yes");
    ++rows;
  }
  CHECK(rows == 2);
  fs::remove_all(w);
}
