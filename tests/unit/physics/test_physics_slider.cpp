// physics/slider.hpp: the spring tension and the slider's equation of motion (Eq. 1).
#include <catch2/catch.hpp>
#include <cmath>

#include "physics/slider.hpp"

using namespace asperity;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;

TEST_CASE("slider: steady sliding without junctions holds Q = M η v and no acceleration", "[physics]") {
  // Paper apparatus. With F = 0, Eq. (1) has the particular solution X = v t − η v / ω²
  // (ω² = k_L/M): the spring carries exactly the damping force M η v.
  const Slider s{0.408, 9200.0, 1e-4, 100.0};
  const double w2 = s.k_L / s.mass_kg;
  for (double t : {0.0, 0.37, 5.0}) {
    const double X = s.v * t - s.eta * s.v / w2;
    const double Q = s.loading_force(t, X);
    CHECK_THAT(Q, WithinRel(s.mass_kg * s.eta * s.v, 3e-13));  // cancellation in v t − X: measured 8.2e-14 at t = 5 s
    // Residual of Eq. (1) relative to the damping term η v = 1e-2 m/s².
    CHECK_THAT(s.acceleration(Q, 0.0, s.v), WithinAbs(0.0, 3e-13 * s.eta * s.v));  // measured 8.2e-14
  }
}

TEST_CASE("slider: acceleration is (Q − F)/M − η Ẋ, η entering only through the velocity", "[physics]") {
  const Slider s{0.5, 100.0, 1e-3, 3.0};
  // Q = 100 (2e-3 − 1e-3) = 0.1 N; (0.1 − 0.04)/0.5 − 3 · 0.01 = 0.09 m/s².
  const double Q = s.loading_force(2.0, 1e-3);
  CHECK_THAT(Q, WithinRel(0.1, 1e-15));
  CHECK_THAT(s.acceleration(Q, 0.04, 0.01), WithinRel(0.09, 1e-14));
  const Slider undamped{0.5, 100.0, 1e-3, 0.0};
  CHECK_THAT(undamped.acceleration(Q, 0.04, 0.01), WithinRel(0.12, 1e-14));
}
