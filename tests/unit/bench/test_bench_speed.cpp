// `bench speed` bookkeeping on made-up runs: accuracy matching (a missing observable counts as the
// worst) and the ratio per simulated second.
#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>
#include <string>

#include "bench/speed_ratio.hpp"

using namespace asperity;

namespace {
SpeedRun made_up(const std::string& method, double wall, double t_end, std::array<double, n_robust> error) {
  SpeedRun r;
  r.method = method;
  r.wall_s = wall;
  r.cpu_s = wall / 2;
  r.t_end = t_end;
  r.steps = 100;
  r.error = error;
  return r;
}
}  // namespace

TEST_CASE("bench speed: accuracy matching and ratio per simulated second", "[bench]") {
  const double nan = std::nan("");
  const SpeedRun ref = made_up("reference", 50.0, 5.0, {1e-5, 1e-5, 1e-5, 1e-4, nan, nan});
  const SpeedRun good = made_up("event", 0.1, 4.0, {1e-7, 1e-8, 1e-7, 1e-8, 1e-4, 1e-4});
  const SpeedRun loose = made_up("event", 0.05, 4.0, {1e-7, 1e-4, 1e-7, 1e-8, 1e-4, 1e-4});
  CHECK(good.at_least_as_accurate_as(ref));         // finite beats a missing stick-slip
  CHECK_FALSE(loose.at_least_as_accurate_as(ref));  // A_s 1e-4 > 1e-5
  CHECK_FALSE(ref.at_least_as_accurate_as(good));   // a missing observable never matches
  CHECK(good.max_loading_error() == 1e-7);
  CHECK(std::isnan(ref.max_stick_slip_error()));
  const SpeedComparison c{"x", "measured", ref, good};
  CHECK(c.ratio_wall() == (50.0 / 5.0) / (0.1 / 4.0));  // 400
  CHECK(c.ratio_cpu() == (25.0 / 5.0) / (0.05 / 4.0));

  SpeedResult r;
  r.experiment = "E";
  r.truth = good;
  r.runs = {ref, good};
  r.comparisons = {c};
  std::istringstream csv(speed_ratio_csv(r));
  std::string header, row, extra;
  REQUIRE(std::getline(csv, header));
  REQUIRE(std::getline(csv, row));
  CHECK_FALSE(std::getline(csv, extra));
  // Same number of fields outside quotes in header and row.
  auto fields = [](const std::string& s) {
    int n = 1;
    bool quoted = false;
    for (char ch : s) {
      if (ch == '"') quoted = !quoted;
      if (ch == ',' && !quoted) ++n;
    }
    return n;
  };
  CHECK(fields(row) == fields(header));
  CHECK(row.substr(row.rfind(',', row.rfind(',') - 1) + 1) == "400,400");
}
