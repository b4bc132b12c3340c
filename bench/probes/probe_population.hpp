#pragma once
// Shared by the probes of issue 26: `bench interacting`'s synthetic populations (the STAND-IN
// P4.00N's areas repeated to N, placed in a disc of radius 4.5 mm · sqrt(N / 1201), run from the
// repository root) and a stopwatch.
#include <chrono>
#include <cmath>
#include <cstddef>
#include <vector>

#include "generate/positions.hpp"
#include "physics/contact_law.hpp"
#include "scene/load.hpp"

struct ProbePopulation {
  std::vector<double> area_m2, radius_m, x_m, y_m;
  double E_pa = 0, nu = 0, disc_radius_m = 0;
};

inline ProbePopulation probe_population(std::size_t N) {
  const asperity::Scene base = asperity::load_scene("scenes/paper/P4.00N.yaml");
  const auto& areas = base.experiment.junctions.area_m2;
  ProbePopulation p;
  p.E_pa = base.experiment.E, p.nu = base.experiment.nu;
  p.disc_radius_m = 4.5e-3 * std::sqrt(double(N) / double(areas.size()));
  p.area_m2.resize(N), p.radius_m.resize(N);
  for (std::size_t i = 0; i < N; ++i)
    p.area_m2[i] = areas[i % areas.size()], p.radius_m[i] = asperity::disc_radius(p.area_m2[i]);
  const asperity::Positions at = asperity::place_in_contact_disc(p.area_m2, p.disc_radius_m, 20200318);
  p.x_m = at.x_m, p.y_m = at.y_m;
  return p;
}

using ProbeClock = std::chrono::steady_clock;
inline double seconds_since(ProbeClock::time_point a) {
  return std::chrono::duration<double>(ProbeClock::now() - a).count();
}
