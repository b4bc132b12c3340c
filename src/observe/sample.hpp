#pragma once
#include <cstdint>

namespace asperity {

// State of the interface at one instant, in SI units. Q = k_L (v t − X), A = Σ A_i.
struct Sample {
  double t = 0, X = 0, V = 0, Q = 0, A = 0;
  std::int64_t n_slipping = 0;  // junctions currently slipping
  std::int64_t n_intact = 0;    // junctions that have never slipped
};

// A local extremum of Q (the slider velocity crosses v: Q' = k_L (v − V) = 0).
struct Extremum {
  double t = 0, Q = 0, A = 0;
  bool is_max = true;
};

// A change of the junction population at time t: `new_slips` junctions started to slip, and/or
// (`stick`) every slipping junction repinned because the slider nearly stopped (|Ẋ| < c_min v).
// n_intact: junctions that have never slipped, after the change.
struct PopulationChange {
  double t = 0;
  std::int64_t new_slips = 0;
  bool stick = false;
  std::int64_t n_intact = 0;
};

}  // namespace asperity
