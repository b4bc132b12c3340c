#pragma once
// Forces of the pinned junctions of an interacting population at slider position X (docs/model.md
// §8): for every junction i being solved,
//   g_i(f_i) + Σ_{j≠i} C_ij f_j = X − x_i,
// with g_i(f) = f / k_i(A_i(f)) when the junction's area follows its force (Eq. 3), f / k_i
// otherwise, and every other junction's force held at its current value. Newton on the dense
// system (LDLT), started from the current forces; a linear system whose set of junctions did
// not change since the last call reuses its factorisation. For the step-by-step interacting
// reference: O(n³) per factorisation.
#include <chrono>
#include <cstdint>
#include <memory>
#include <vector>

#include "solve/core/junction_state.hpp"
#include "solve/core/problem.hpp"
#include "solve/interacting/interaction_matrix.hpp"

namespace asperity {

class CoupledForces {
 public:
  CoupledForces(const Problem& problem, const InteractionMatrix& C);
  ~CoupledForces();
  CoupledForces(const CoupledForces&) = delete;
  CoupledForces& operator=(const CoupledForces&) = delete;

  // Solves the junctions with solve[i] != 0 at slider position X_m: writes J.force and, where
  // the area follows the force, J's contact. Returns the Newton iterations (SolverError when it
  // does not converge in 100). From the deadline on, a further Newton iteration (each a dense
  // factorisation, a minute at N = 20,000) throws WallTimeReached instead, J unchanged.
  int solve(JunctionState& J, const std::vector<std::uint8_t>& solve, double X_m,
            std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::time_point::max());

 private:
  struct Factorisation;
  const Problem& p_;
  const InteractionMatrix& C_;
  std::unique_ptr<Factorisation> cached_;  // of the last linear system
  std::vector<std::size_t> cached_set_;
};

}  // namespace asperity
