// solve/core/run_cost.hpp: the cost model campaigns balance their shards by, against the
// committed benchmarks it was fitted to (wall seconds on one thread of the development machine).
// A benchmark rerun after a solver change moves these rows; this test then says which constant of
// run_cost.cpp has gone stale.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "io/csv.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_cost.hpp"
#include "support_scenes.hpp"

using namespace asperity;
using namespace asperity::testing;

namespace {
const std::filesystem::path kSource(ASPERITY_SOURCE_DIR);

// The rows of a committed CSV as column → text.
std::vector<std::map<std::string, std::string>> rows_of(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  REQUIRE(std::getline(in, line));
  const std::vector<std::string> head = io::csv_split(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> f = io::csv_split(line);
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < head.size() && k < f.size(); ++k) row[head[k]] = f[k];
    rows.push_back(row);
  }
  return rows;
}

// A scene of n junctions of the stand-in P4.00N's mean size in a row 1 mm apart (the cost
// model reads only N, the span, the solver and whether junctions interact).
Scene row_scene(std::size_t n, double t_stop, bool interacting) {
  std::vector<double> x(n), y(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) x[i] = 1e-3 * static_cast<double>(i);
  Scene s = interacting ? interacting_scene(std::vector<double>(n, 1.4e-8), x, y, SolverMethod::event)
                        : paper_scene(std::vector<double>(n, 1.4e-8));
  s.stop.time = t_stop;
  return s;
}
}  // namespace

TEST_CASE("run cost: the model is within a factor of two of the committed benchmarks", "[solve]") {
  // The interacting event solver to its first peak (bench interacting, one thread): 1.0 times
  // the measured wall at N = 300 and 5,000, 1.42 times at 1,200 (the model's a N² + b N per
  // simulated second passes through the end points).
  int checked = 0;
  for (const auto& row : rows_of(kSource / "results/bench/interacting.csv")) {
    if (row.at("what") != "first_peak") continue;
    const std::size_t n = std::stoul(row.at("N"));
    const double wall = std::stod(row.at("wall_s")), t_end = std::stod(row.at("t_end_s"));
    const double model = expected_run_seconds(make_problem(row_scene(n, t_end, true)));
    INFO("N = " << n << ": model " << model << " s, measured " << wall << " s");
    CHECK(model / wall < 2.0);
    CHECK(wall / model < 2.0);
    ++checked;
  }
  CHECK(checked >= 3);
  // The independent event solver over the stand-in P4.00N's whole run at its default tolerance
  // (1e-9: 0.170 s for 5.70 s simulated, N = 1,201): 1.0 times.
  checked = 0;
  for (const auto& row : rows_of(kSource / "results/bench/speed_runs.csv")) {
    if (row.at("experiment") != "P4.00N" || row.at("method") != "event" || row.at("setting") != "1e-09") continue;
    const double model = expected_run_seconds(make_problem(row_scene(1201, std::stod(row.at("t_end_s")), false)));
    const double wall = std::stod(row.at("wall_s"));
    INFO("independent event: model " << model << " s, measured " << wall << " s");
    CHECK(model / wall < 2.0);
    CHECK(wall / model < 2.0);
    ++checked;
  }
  CHECK(checked == 1);
}
