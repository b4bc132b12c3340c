#pragma once
// What a run reports besides its samples: initial quantities, where it stopped, its counts.
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include "solve/core/run_limits.hpp"

namespace asperity {

// A run that cannot go on (unstable step, non-finite state): reported, never silent garbage.
struct SolverError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct SolverStats {
  std::int64_t steps = 0;        // accepted steps
  std::int64_t rejected = 0;     // rejected steps (adaptive solvers)
  std::int64_t force_evals = 0;  // evaluations of the total junction force
  std::int64_t slips = 0;        // pinned → slipping transitions
  std::int64_t repins = 0;       // repinning events (all slipping junctions at once)
};

struct RunInfo {
  std::size_t N = 0;
  double A0 = 0;                         // m², Σ A0_i
  double K0 = 0;                         // N/m, Σ k_i(t = 0)
  double T0 = 0;                         // s, 2π / sqrt(K0 / M)
  double dt = 0;                         // s, T0 / C_t (the reference's step; reported for every method)
  double t_end = 0;                      // s, where the run stopped
  LimitHit stopped_by = LimitHit::none;  // a resource limit ended the run before stop.time
  double max_f_over_sigmaA = 0;          // max_i,t f_i / (σ A_i) after transitions (claim 7: ≤ 1)
  double max_f_over_sigma_exp_A = 0;     // the same against σ_exp (may exceed 1)
  SolverStats stats;
};

}  // namespace asperity
