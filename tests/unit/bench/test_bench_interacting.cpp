// bench/interacting.hpp: the exponent of the interacting solver's time in N.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "bench/interacting.hpp"

TEST_CASE("bench interacting: the time exponent of N from two sizes or more, none from one", "[bench]") {
  using asperity::InteractingBenchRow;
  // wall ∝ N³ exactly: 1 s at 300, 8 s at 600, 27 s at 900 → b = 3.
  std::vector<InteractingBenchRow> rows(3);
  const std::size_t N[] = {300, 600, 900};
  for (int i = 0; i < 3; ++i) rows[i].what = "first_peak", rows[i].N = N[i], rows[i].wall_s = std::pow(N[i] / 300.0, 3);
  rows.push_back({"whole_run", 1201, 99.0});  // not a scaling row
  CHECK_THAT(asperity::fitted_exponent(rows), Catch::Matchers::WithinAbs(3.0, 1e-12));
  CHECK_THAT(asperity::fitted_exponent_text(rows), Catch::Matchers::Contains("N^3 (least squares over N = 300..900)"));
  // One size (or the same size twice): no exponent, said in words, never "N^nan".
  for (const std::size_t n : {1u, 2u}) {
    std::vector<InteractingBenchRow> one(n, rows[0]);
    CHECK(std::isnan(asperity::fitted_exponent(one)));
    CHECK_THAT(asperity::fitted_exponent_text(one), Catch::Matchers::Contains("no exponent from one size (N = 300)"));
    CHECK_THAT(asperity::fitted_exponent_text(one), !Catch::Matchers::Contains("nan"));
  }
}

TEST_CASE("bench interacting: recording the output series costs no exact solve and changes nothing", "[bench]") {
  // Samples are taken on the cached F(X), A(X) pieces between events (issue 26 item 2): the run
  // with the scene's output series must do exactly the solves, chord iterations and steps of the
  // run without, and reach the same first peak to the bit.
  asperity::InteractingBenchOptions o;
  o.scene = std::string(ASPERITY_SOURCE_DIR) + "/scenes/paper/P0.98N.yaml";
  o.sizes = {120};
  o.contact_radius_m = 2.8e-3;
  o.whole_run = false;
  o.converged_tolerance = 0;
  const auto rows = asperity::run_interacting_bench(o);
  REQUIRE(rows.size() == 2);
  const auto& w = rows[0];
  const auto& r = rows[1];
  REQUIRE(w.what == "first_peak_series");
  REQUIRE(r.what == "first_peak");
  CHECK(w.samples > 1000);  // a sample every output.every (1 ms) to t_peak (> 1 s)
  CHECK(r.samples <= 1);
  CHECK(w.slips == r.slips);
  CHECK(w.solves == r.solves);
  CHECK(w.iterations == r.iterations);
  CHECK(w.steps == r.steps);
  CHECK(w.Q_s == r.Q_s);
  CHECK(w.t_peak == r.t_peak);
}
