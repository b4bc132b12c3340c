// `asperity bench`: bad input is reported with the file named; accuracy writes its CSV; --redraw
// draws savings.png from a committed CSV and refuses a bad one at its line.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "report/gnuplot.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;

namespace {

using asperity::testing::slurp;

int run_cli(const std::string& args, const fs::path& work, std::string* err) {
  const std::string cmd =
      "cd '" + work.string() + "' && '" + ASPERITY_BINARY + "' " + args + " >stdout.txt 2>stderr.txt";
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

TEST_CASE("bench speed: whole-run ratios follow from the runs, the extrapolation counts the steps at C_t 1e4",
          "[bench][cli]") {
  const fs::path w = fs::temp_directory_path() / ("asperity-bench-speed-" + std::to_string(::getpid()));
  fs::remove_all(w);
  fs::create_directories(w);
  const std::string scene = std::string(ASPERITY_SOURCE_DIR) + "/bench/scenes/P0.20N.yaml";
  std::string err;
  REQUIRE(run_cli("bench speed --quick --scene '" + scene + "' --ct 10 20 --window 1e-3 --out out", w, &err) == 0);
  // speed_runs.csv: the truth first, then the event and reference runs.
  std::istringstream runs_csv(slurp(w / "out" / "speed_runs.csv"));
  std::string line;
  REQUIRE(std::getline(runs_csv, line));
  double T_run = 0, ref_cpu = 0, ref_t = 0, ref_steps = 0, ev_cpu = 0, ev_t = 0;
  int n_runs = 0;
  while (std::getline(runs_csv, line)) {
    const auto f = split(line);  // experiment,method,setting,span,t_end_s,steps,cycles,repeats,wall_s,cpu_s,...
    REQUIRE(f.size() == 18);
    if (n_runs++ == 0) T_run = std::stod(f[4]);
    if (f[1] == "event" && f[2] == "1e-09") ev_cpu = std::stod(f[9]), ev_t = std::stod(f[4]);
    if (f[1] == "reference" && f[2] == "20" && f[3] == "whole run")
      ref_cpu = std::stod(f[9]), ref_t = std::stod(f[4]), ref_steps = std::stod(f[5]);
  }
  CHECK(n_runs == 1 + 3 + 2 + 2);  // truth, default + 2 quick tolerances, 2 whole, 2 windows
  REQUIRE(ref_steps > 0);
  REQUIRE(ev_cpu > 0);
  // The reference's whole run spans the truth's T_run (one step beyond at most).
  CHECK(ref_t > T_run - 1e-7);  // 8 digits in the CSV
  CHECK(ref_t - T_run < ref_t / ref_steps);
  // dt at C_t 1e4 from the scene, independently of the bench code.
  const double dt = asperity::initial_info(asperity::load_scene(scene, {"solver.Ct=10000"})).dt;
  const double target_steps = std::ceil(T_run / dt - 1e-9);
  const std::string ratios = slurp(w / "out" / "speed_ratio.csv");
  std::istringstream ratio_csv(ratios);
  REQUIRE(std::getline(ratio_csv, line));
  int rows = 0;
  while (std::getline(ratio_csv, line)) {
    ++rows;
    // Quoted texts first; the numeric tail holds no quotes: reference_Ct … ratio_cpu (16 fields).
    const auto tail = split(line.substr(line.rfind('"') + 2));
    REQUIRE(tail.size() == 16);
    const double ratio_cpu = std::stod(tail[15]);
    if (line.find("measured, both over the whole run") != std::string::npos && tail[8] == "1e-09") {
      // ratio = (reference CPU per simulated second) / (event CPU per simulated second); the CSV
      // rounds it to 3 digits (≤ 5e-3) and the CPU times to 4.
      CHECK(std::abs(ratio_cpu / ((ref_cpu / ref_t) / (ev_cpu / ev_t)) - 1) < 7e-3);
    }
    if (line.find("reference extrapolated") != std::string::npos) {
      CHECK(std::stod(tail[0]) == 1e4);
      CHECK(std::stod(tail[2]) == target_steps);
      // Reference CPU = its per-step CPU at C_t 20 × the step count at 1e4 (4 digits).
      CHECK(std::abs(std::stod(tail[5]) / (ref_cpu / ref_steps * target_steps) - 1) < 1e-3);
    }
  }
  CHECK(rows >= 3);  // whole run, extrapolated, window (+ equal accuracy when a tolerance matches)
  fs::remove_all(w);
}

TEST_CASE("bench savings --redraw: the committed CSV redrawn, a bad one refused in one line", "[bench][cli]") {
  const fs::path w = fs::temp_directory_path() / ("asperity-bench-redraw-" + std::to_string(::getpid()));
  fs::remove_all(w);
  fs::create_directories(w / "out");
  const fs::path source = ASPERITY_SOURCE_DIR;
  const std::string csv = slurp(source / "results/bench/savings.csv");
  asperity::testing::write_text(w / "out/savings.csv", csv);
  const std::string scene = " --scene '" + (source / "scenes/paper/P4.00N.yaml").string() + "'";
  std::string err;
  CHECK(run_cli("bench savings --redraw --out out" + scene, w, &err) == (asperity::io::gnuplot_available() ? 0 : 1));
  CHECK_THAT(slurp(w / "out/savings.gp"), Catch::Matchers::Contains(asperity::kStandInMark));
  CHECK(slurp(w / "out/savings.csv") == csv);
  // The third line's cpu_s (sixth column) not a number: that line and column, exit 2.
  std::string bad = csv;
  std::size_t at = 0;
  for (int line = 1; line < 3; ++line) at = bad.find('\n', at) + 1;
  for (int comma = 0; comma < 5; ++comma) at = bad.find(',', at) + 1;
  bad.insert(at, "x");
  asperity::testing::write_text(w / "out/savings.csv", bad);
  CHECK(run_cli("bench savings --redraw --out out" + scene, w, &err) == 2);
  CHECK_THAT(err, Catch::Matchers::StartsWith("out/savings.csv:3:6: cpu_s: expected a number, got 'x"));
  CHECK(std::count(err.begin(), err.end(), '\n') == 1);
  CHECK(run_cli("bench tradeoff --redraw --out out", w, &err) == 2);
  CHECK_THAT(err, Catch::Matchers::StartsWith("out/work_precision.csv: file not found"));
  fs::remove_all(w);
}
