// solve/interacting/chord_policy.hpp: the chord iteration's stopping and rebuild rules.
#include <catch2/catch.hpp>
#include <cmath>

#include "solve/interacting/chord_policy.hpp"

using asperity::ChordPolicy;

TEST_CASE("chord policy: a change within the tolerance converges on any pass", "[interacting][chord_policy]") {
  const ChordPolicy p{1e-8};
  CHECK(p.converged(1, 1e-8, HUGE_VAL));
  CHECK(p.converged(1, 0.0, HUGE_VAL));
  CHECK_FALSE(p.converged(1, 2e-8, HUGE_VAL));
  CHECK_FALSE(p.converged(2, 2e-8, 1.0));
}

TEST_CASE("chord policy: the rate estimate stops a fast contraction early", "[interacting][chord_policy]") {
  const ChordPolicy p{1e-8};
  // ρ = 0.1: the iterate is about change · ρ/(1 − ρ) = 2.2e-9 from the fixed point.
  CHECK(p.within_by_rate(3, 2e-8, 2e-7));
  CHECK_FALSE(p.within_by_rate(2, 2e-8, 2e-7));  // not before the third pass
  // ρ = 0.45: 7.4e-8 from it, over the tolerance.
  CHECK_FALSE(p.within_by_rate(3, 9e-8, 2e-7));
  // Never above ten times the tolerance, nor without contracting by half.
  CHECK_FALSE(p.within_by_rate(3, 2e-7, 1.0));
  CHECK_FALSE(p.within_by_rate(3, 2e-8, 3e-8));
}

TEST_CASE("chord policy: a change stalled at rounding stops the solve", "[interacting][chord_policy]") {
  const ChordPolicy tight{1e-13};
  CHECK(tight.stalled(3, 5e-13, 6e-13));
  CHECK_FALSE(tight.stalled(2, 5e-13, 6e-13));
  CHECK_FALSE(tight.stalled(3, 5e-13, 2e-12));  // still halving
  // At the default tolerance the rounding bound is 1e-11: a solve above it is not stalled.
  const ChordPolicy loose{1e-8};
  CHECK_FALSE(loose.stalled(3, 2e-11, 3e-11));
  CHECK(loose.stalled(3, 5e-12, 6e-12));
}

TEST_CASE("chord policy: slow passes, and when a rebuild is worth them", "[interacting][chord_policy]") {
  const ChordPolicy p{1e-8};
  CHECK(p.slow(3, 0.3, 1.0));  // contracting by 0.3, far from the tolerance
  CHECK_FALSE(p.slow(3, 0.1, 1.0));
  CHECK_FALSE(p.slow(2, 0.3, 1.0));  // not before the third pass
  CHECK(p.slow(3, 6e-8, 1e-7));      // by 0.6 within ten times the tolerance
  CHECK_FALSE(p.slow(3, 3e-8, 1e-7));
  CHECK_FALSE(p.slow(3, 0.9e-8, 1e-8));  // within the tolerance: not slow
  // Rent or buy: the slow passes pay for a rebuild (n/8 passes) first.
  CHECK_FALSE(ChordPolicy::rebuild_worth(124, 1000, 0.5, 1.0, 5));
  CHECK(ChordPolicy::rebuild_worth(125, 1000, 0.5, 1.0, 5));
  CHECK(ChordPolicy::rebuild_worth(1, 1000, 1.5, 1.0, 5));   // growing
  CHECK(ChordPolicy::rebuild_worth(1, 1000, 0.5, 1.0, 20));  // long
  CHECK(p.stuck() == Approx(1e-6));
  CHECK(ChordPolicy{1e-3}.stuck() == 1e-2);
}
