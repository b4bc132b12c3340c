#pragma once
// One run as the steppers see it: plain arrays and constants, built once from a Scene. No YAML
// and no Scene inside a stepper.
#include <cstddef>
#include <vector>

#include "physics/contact_law.hpp"
#include "physics/slider.hpp"
#include "scene/scene.hpp"
#include "solve/core/run_info.hpp"
#include "solve/core/run_limits.hpp"

namespace asperity {

struct Problem {
  std::vector<double> A0;  // m², initial junction areas
  ContactLaw law;          // σ = σ_exp/ε (docs/model.md §2)
  AreaLaw area_law = AreaLaw::until_first_slip;
  Slider slider;          // M, k_L, v, η
  double c_min = 0;       // repinning when |Ẋ| < c_min v
  double t_stop = 0;      // s, stop.time
  SolverSettings solver;  // method, C_t, tolerance
  RunLimits limits;       // checked every step or event
  // Derived once: Σ A0 [m²], Σ k_i(t = 0) [N/m], T0 = 2π / sqrt(K0/M) [s], dt = T0/C_t [s].
  double A0_sum = 0, K0 = 0, T0 = 0, dt = 0;
  // Elastic interactions (docs/model.md §8), when the scene asks for them: junction centres [m] and
  // the distance beyond which pairs are dropped [m] (0: none dropped). Empty x: independent.
  std::vector<double> x, y;
  double interaction_cutoff = 0;
  TractionWeighting interaction_weighting = TractionWeighting::uniform;
  bool interacting() const { return !x.empty(); }

  std::size_t size() const { return A0.size(); }
  double repin_speed() const { return c_min * slider.v; }  // m/s
};

Problem make_problem(const Scene& scene, const RunLimits& limits);
inline Problem make_problem(const Scene& scene) { return make_problem(scene, run_limits(scene)); }

// The initial quantities of a run (N, A0, K0, T0, dt), before any step.
RunInfo initial_info(const Problem& problem);
RunInfo initial_info(const Scene& scene);

}  // namespace asperity
