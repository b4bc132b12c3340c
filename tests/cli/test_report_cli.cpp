// End to end: `asperity run` writes a run directory whose scene.yaml repeats the run exactly,
// and maps bad input / solver failure to exit codes 2 / 3.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support_files.hpp"

namespace fs = std::filesystem;

namespace {

using asperity::testing::slurp;
std::string q(const fs::path& p) { return asperity::testing::shell_quoted(p); }

// Runs the asperity binary with `args`; returns its exit status, stderr in `err`.
int run_cli(const std::string& args, const fs::path& work, std::string* err = nullptr) {
  const fs::path errf = work / "stderr.txt";
  const std::string cmd =
      "cd " + q(work) + " && " + q(ASPERITY_BINARY) + " " + args + " >" + q(work / "stdout.txt") + " 2>" + q(errf);
  const int rc = std::system(cmd.c_str());
  if (err) *err = slurp(errf);
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// summary.yaml without the lines that legitimately differ between two identical runs.
std::string stable_summary(const fs::path& dir) {
  std::istringstream in(slurp(dir / "summary.yaml"));
  std::string out;
  for (std::string line; std::getline(in, line);) {
    if (line == "provenance:") break;  // the command line and file paths differ by design
    if (line.rfind("wall_s:", 0) != 0 && line.rfind("scene_file:", 0) != 0) out += line + "\n";
  }
  return out;
}

fs::path make_case() {
  const fs::path w = fs::temp_directory_path() / ("asperity-cli-test-" + std::to_string(::getpid()));
  fs::remove_all(w);
  fs::create_directories(w / "exp");
  fs::create_directories(w / "scenes");
  std::ofstream(w / "exp" / "junctions.csv") << "area_m2\n1e-8\n2.5e-8\n4e-8\n";
  std::ofstream(w / "exp" / "experiment.yaml")
      << "name: cli-test\nmass: 0.1\nk_L: 9200\nv: 1.0e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 0.23e6\n"
         "junctions: junctions.csv\n";
  std::ofstream(w / "scenes" / "tiny.yaml") << "experiment: ../exp/experiment.yaml\n"
                                               "solver: {method: reference, Ct: 200}\n"
                                               "stop: {time: 0.02}\n"
                                               "output: {every: 1.0e-3}\n";
  return w;
}

}  // namespace

TEST_CASE("asperity run writes a run directory whose scene.yaml repeats the run", "[report][observe]") {
  const fs::path w = make_case();
  std::string err;
  REQUIRE(run_cli("run scenes/tiny.yaml --quiet --set model.eta=50", w, &err) == 0);
  INFO(err);
  const fs::path d1 = w / "results" / "runs" / "tiny";  // default: results/runs/<stem>/
  REQUIRE(fs::exists(d1 / "summary.yaml"));
  REQUIRE(fs::exists(d1 / "series.csv"));
  CHECK(slurp(d1 / "series.csv").rfind("t,X,V,Q,A,n_slipping,n_intact\n", 0) == 0);
  CHECK(slurp(w / "stdout.txt").empty());

  REQUIRE(run_cli("run " + q(d1 / "scene.yaml") + " --out again", w, &err) == 0);
  const fs::path d2 = w / "again";
  CHECK(stable_summary(d1) == stable_summary(d2));
  CHECK(slurp(d1 / "series.csv") == slurp(d2 / "series.csv"));
  CHECK(slurp(d1 / "scene.yaml") == slurp(d2 / "scene.yaml"));
  CHECK(slurp(w / "stdout.txt").find("Q_s") != std::string::npos);
  fs::remove_all(w);
}

TEST_CASE("asperity run: bad input exits 2 with one line, solver failure exits 3", "[report][observe]") {
  const fs::path w = make_case();
  std::string err;
  CHECK(run_cli("run scenes/tiny.yaml --out bad --set model.epsilon=1.5", w, &err) == 2);
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK(err.find("model.epsilon") != std::string::npos);
  CHECK_FALSE(fs::exists(w / "bad"));

  CHECK(run_cli("run scenes/missing.yaml --out bad", w, &err) == 2);
  CHECK_FALSE(fs::exists(w / "bad"));

  // C_t = 1: the explicit step is unstable and the reference solver refuses to run.
  CHECK(run_cli("run scenes/tiny.yaml --out bad --set solver.Ct=1", w, &err) == 3);
  CHECK(err.find("unstable") != std::string::npos);
  CHECK_FALSE(fs::exists(w / "bad"));
  fs::remove_all(w);
}
