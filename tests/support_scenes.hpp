#pragma once
// Scenes built in code for solver tests (the paper's apparatus and defaults): scene level.
#include <cmath>
#include <vector>

#include "scene/scene.hpp"

namespace asperity::testing {

inline Scene paper_scene(std::vector<double> areas, double mass = 0.408) {
  Scene s;
  auto& e = s.experiment;
  e.name = "test";
  e.mass_kg = mass;
  e.k_L = 9200;
  e.v = 1e-4;
  e.E = 1.6e6;
  e.nu = 0.5;
  e.sigma_exp = 0.23e6;
  e.junctions.area_m2 = std::move(areas);
  s.stop.time = 1.0;
  s.output.every = 1e-3;
  return s;
}

// paper_scene with junction centres [m] and elastic interactions, run by `method`.
inline Scene interacting_scene(std::vector<double> areas, std::vector<double> x, std::vector<double> y,
                               SolverMethod method) {
  Scene s = paper_scene(std::move(areas));
  s.experiment.junctions.x_m = std::move(x);
  s.experiment.junctions.y_m = std::move(y);
  s.model.interactions = Interactions::elastic;
  s.solver.method = method;
  return s;
}

// Deterministic spread of areas on [lo, hi] (log-uniform, no RNG).
inline std::vector<double> spread_areas(std::size_t n, double lo, double hi) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i)
    a[i] = lo * std::pow(hi / lo, (static_cast<double>(i) + 0.5) / static_cast<double>(n));
  return a;
}

}  // namespace asperity::testing
