#pragma once
// Per-junction physical state, one layout for every method (structure of arrays for vectorised
// loops). A method may keep acceleration structures beside it (the event method's threshold
// heap and aggregate sums), but the physical state of junction i is here.
#include <cstdint>
#include <vector>

#include "physics/interface_law.hpp"

namespace asperity {

struct JunctionState {
  std::vector<double> A0;            // m², initial area
  std::vector<double> anchor;        // m, x_i: the pinned junction's force is zero at X = x_i
  std::vector<double> force;         // N, f_i
  std::vector<double> area;          // m², A_i
  std::vector<double> k;             // N/m, k_i(A_i)
  std::vector<double> f_s;           // N, static threshold σ A_i
  std::vector<std::uint8_t> pinned;  // θ_i
  std::vector<std::uint8_t> intact;  // h_i: never slipped

  // All junctions pinned at X = 0, unloaded, never slipped.
  JunctionState(const std::vector<double>& areas, const ContactLaw& law);
  std::size_t size() const { return A0.size(); }
  // Sets area, k and f_s of junction i.
  void set_contact(std::size_t i, const JunctionContact& c) {
    area[i] = c.area_m2;
    k[i] = c.k;
    f_s[i] = c.f_s;
  }
};

}  // namespace asperity
