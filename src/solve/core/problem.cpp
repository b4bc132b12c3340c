#include "solve/core/problem.hpp"

#include <cmath>

namespace asperity {

Problem make_problem(const Scene& scene, const RunLimits& limits) {
  const auto& e = scene.experiment;
  const auto& m = scene.model;
  Problem p;
  p.A0 = e.junctions.area_m2;
  p.law = make_contact_law(e, m);
  p.area_law = m.area_law;
  p.slider = Slider{e.mass_kg, e.k_L, e.v, m.eta};
  p.c_min = m.c_min;
  p.t_stop = scene.stop.time;
  p.solver = scene.solver;
  p.limits = limits;
  for (double a : p.A0) {
    p.A0_sum += a;
    p.K0 += p.law.stiffness(a, a);
  }
  if (m.interactions == Interactions::elastic) {
    p.x = e.junctions.x_m;
    p.y = e.junctions.y_m;
    for (double& v : p.x) v *= m.position_scale;
    for (double& v : p.y) v *= m.position_scale;
    p.interaction_cutoff = m.interaction_cutoff;
    p.interaction_weighting = m.interaction_weighting;
  }
  p.T0 = 2.0 * M_PI / std::sqrt(p.K0 / e.mass_kg);
  p.dt = p.T0 / scene.solver.Ct;
  return p;
}

RunInfo initial_info(const Problem& p) {
  RunInfo info;
  info.N = p.size();
  info.A0 = p.A0_sum;
  info.K0 = p.K0;
  info.T0 = p.T0;
  info.dt = p.dt;
  return info;
}

RunInfo initial_info(const Scene& scene) { return initial_info(make_problem(scene)); }

}  // namespace asperity
