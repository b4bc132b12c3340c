// solve/core/problem.hpp: the Problem a stepper runs, built once from a Scene.
#include <catch2/catch.hpp>
#include <cmath>

#include "solve/core/problem.hpp"
#include "support_scenes.hpp"

using namespace asperity;
using namespace asperity::testing;
using Catch::Matchers::WithinRel;

TEST_CASE("Problem: constants of the scene and the initial stiffness of round junctions", "[solve]") {
  Scene s = paper_scene(std::vector<double>(10, 1e-8), 0.3);
  s.model.junction_shape = JunctionShape::circular;
  s.model.eta = 50;
  s.solver.Ct = 2000;
  const Problem p = make_problem(s);
  CHECK(p.size() == 10);
  CHECK(p.slider.mass_kg == 0.3);
  CHECK(p.slider.k_L == 9200);
  CHECK(p.slider.eta == 50);
  CHECK_THAT(p.law.sigma, WithinRel(0.23e6 / 0.9, 1e-15));
  CHECK_THAT(p.repin_speed(), WithinRel(0.01 * 1e-4, 1e-15));
  CHECK(p.limits.max_slips == default_max_slips(s));
  // Circle formula: k = E ℓ0 / ((1+ν)(1−ν/2)), ℓ0 = sqrt(4 A0/π); T0 = 2π sqrt(M/K0).
  const double k = 1.6e6 * std::sqrt(4e-8 / M_PI) / (1.5 * 0.75);
  CHECK_THAT(p.A0_sum, WithinRel(1e-7, 1e-14));
  CHECK_THAT(p.K0, WithinRel(10 * k, 1e-14));
  CHECK_THAT(p.T0, WithinRel(2 * M_PI * std::sqrt(0.3 / (10 * k)), 1e-14));
  CHECK_THAT(p.dt, WithinRel(p.T0 / 2000, 1e-15));
  const RunInfo info = initial_info(s);
  CHECK(info.N == 10);
  CHECK(info.K0 == p.K0);
  CHECK(info.dt == p.dt);
}

TEST_CASE("Problem: limits passed in replace the scene's", "[solve]") {
  const Scene s = paper_scene({1e-8});
  RunLimits l;
  l.max_slips = 7;
  l.wall_time_s = 2.5;
  const Problem p = make_problem(s, l);
  CHECK(p.limits.max_slips == 7);
  CHECK(p.limits.wall_time_s == 2.5);
  CHECK(make_problem(s).limits.wall_time_s == s.stop.wall_time);
}
