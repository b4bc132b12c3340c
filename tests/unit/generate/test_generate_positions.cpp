// generate/positions.hpp: stand-in junction centres in a Hertz-like contact disc.
#include <catch2/catch.hpp>
#include <cmath>

#include "generate/distributions.hpp"
#include "generate/positions.hpp"
#include "scene/validate.hpp"

using namespace asperity;

TEST_CASE("junctions are placed inside the disc without overlap, the same for the same seed", "[generate][positions]") {
  const JunctionPopulation pop = draw_population(Distribution{PowerLaw{1.5, 1e-9, 1e-7}}, 1200, 11);
  const double R = 3.5e-3;
  const Positions a = place_in_contact_disc(pop.area_m2, R, 5), b = place_in_contact_disc(pop.area_m2, R, 5);
  CHECK(a.x_m == b.x_m);
  CHECK(a.y_m == b.y_m);
  CHECK(place_in_contact_disc(pop.area_m2, R, 6).x_m != a.x_m);
  JunctionPopulation placed = pop;
  placed.x_m = a.x_m;
  placed.y_m = a.y_m;
  CHECK_FALSE(first_overlap(placed).has_value());  // the loader's own test
  for (std::size_t i = 0; i < pop.size(); ++i) CHECK(std::hypot(a.x_m[i], a.y_m[i]) < R);
}

TEST_CASE("the density of centres follows the Hertz pressure sqrt(1 - r^2/R^2)", "[generate][positions]") {
  // Small junctions (1 % coverage): exclusion barely matters. Under the Hertz density the
  // fraction of centres within r is 1 − (1 − r²/R²)^(3/2): 0.3505 within R/2.
  const std::vector<double> areas(6000, M_PI * 1e-6 * 1e-6);
  const double R = std::sqrt(6000 * 1e-12 / 0.01);  // 6000 discs of radius 1 µm cover 1 % of it
  const Positions p = place_in_contact_disc(areas, R, 99);
  for (const double r_over_R : {0.3, 0.5, 0.8}) {
    std::size_t inside = 0;
    for (std::size_t i = 0; i < areas.size(); ++i) inside += std::hypot(p.x_m[i], p.y_m[i]) < r_over_R * R;
    const double expected = 1 - std::pow(1 - r_over_R * r_over_R, 1.5);
    const double sd = std::sqrt(expected * (1 - expected) / areas.size());  // binomial
    INFO("r/R " << r_over_R << ": " << inside / 6000.0 << " vs " << expected);
    CHECK(std::abs(inside / 6000.0 - expected) < 4 * sd);
  }
}

TEST_CASE("a disc too small for the junctions is refused with a message", "[generate][positions]") {
  const std::vector<double> areas(100, 1e-8);  // 1e-6 m² of junctions
  CHECK_THROWS_WITH(place_in_contact_disc(areas, 4e-4, 1, 2000), Catch::Contains("raise the contact radius"));
  CHECK_THROWS_AS(place_in_contact_disc(areas, 0, 1), std::invalid_argument);
}
