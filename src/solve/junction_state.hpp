#pragma once
// Per-junction state shared by the solvers (structure of arrays for vectorised loops).
#include <cstdint>
#include <vector>

#include "physics/contact_law.hpp"

namespace asperity {

struct JunctionState {
  std::vector<double> A0;      // m², initial area
  std::vector<double> anchor;  // m, x_i: the pinned junction's force is zero at X = x_i
  std::vector<double> force;   // N, f_i
  std::vector<double> area;    // m², A_i
  std::vector<double> k;       // N/m, k_i(A_i)
  std::vector<double> f_s;     // N, static threshold σ A_i
  std::vector<std::uint8_t> pinned;  // θ_i
  std::vector<std::uint8_t> intact;  // h_i: never slipped

  // All junctions pinned at X = 0, unloaded, never slipped.
  JunctionState(const std::vector<double>& areas, const ContactLaw& law);
  std::size_t size() const { return A0.size(); }
};

}  // namespace asperity
