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
