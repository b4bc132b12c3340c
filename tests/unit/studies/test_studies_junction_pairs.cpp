// Junction pairs in time (report/junction_pairs): the recorded force of each junction against
// the 2x2 closed form of a linear pair, the area against Eq. (3) at the recorded force, the
// first slip between the last sample below the threshold and the first at ε times it, and the
// crowded/sparse pairing.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "physics/elastic_interaction.hpp"
#include "solve/core/problem.hpp"
#include "studies/junction_pairs.hpp"
#include "support_scenes.hpp"

using namespace asperity;
using namespace asperity::testing;
using Catch::Matchers::WithinRel;

TEST_CASE("junction traces follow the 2x2 closed form of a linear pair, then slip at the threshold",
          "[report][pairs]") {
  Scene s = interacting_scene({1e-9, 2.5e-9}, {0, 8e-5}, {0, 3e-5}, SolverMethod::event);
  s.model.alpha_b = 0;
  const Problem p = make_problem(s);
  const double a = 1 / p.law.stiffness(1e-9, 1e-9), d = 1 / p.law.stiffness(2.5e-9, 2.5e-9);
  const double c = disc_compliance(-8e-5, -3e-5, std::sqrt(1e-9 / M_PI), std::sqrt(2.5e-9 / M_PI), p.law.E, p.law.nu);
  const double det = a * d - c * c;
  // The first slip at X = σ A_i det / (coefficient): run to well past it.
  const double sigma = p.law.sigma;
  const double X1 = sigma * 1e-9 * det / (d - c), X2 = sigma * 2.5e-9 * det / (a - c);
  const std::size_t first = X1 < X2 ? 0 : 1;
  const double t_slip = std::min(X1, X2) / p.slider.v;  // X ≈ v t while the slider sticks to the drive
  const auto traces = trace_junctions(s, {0, 1}, 3 * t_slip, 300);
  REQUIRE(traces.size() == 2);
  REQUIRE(traces[first].t_s.size() == 301);
  REQUIRE(std::isfinite(traces[first].first_slip_s));
  std::size_t checked = 0;
  for (std::size_t k = 0; k < traces[0].t_s.size(); ++k) {
    if (traces[0].t_s[k] >= traces[first].first_slip_s) break;
    const double X = traces[0].X_m[k];
    CHECK_THAT(traces[0].f_N[k], WithinRel(X * (d - c) / det, 1e-12));
    CHECK_THAT(traces[1].f_N[k], WithinRel(X * (a - c) / det, 1e-12));
    CHECK(traces[first].f_N[k] < sigma * traces[first].A_m2[k]);
    ++checked;
  }
  CHECK(checked > 10);
  // The first sample after the slip: the junction carries ε σ A (the slipping force).
  const JunctionTrace& tr = traces[first];
  std::size_t after = 0;
  while (tr.t_s[after] < tr.first_slip_s) ++after;
  REQUIRE(after > 0);
  CHECK_THAT(tr.f_N[after], WithinRel(p.law.epsilon * sigma * tr.A_m2[after], 1e-12));
}

TEST_CASE("junction traces carry Eq. (3)'s area at the recorded force", "[report][pairs]") {
  Scene s = interacting_scene({1e-9, 2.5e-9, 1.5e-9}, {0, 8e-5, -6e-5}, {0, 3e-5, 5e-5}, SolverMethod::event);
  REQUIRE(s.model.alpha_b > 0);
  const Problem p = make_problem(s);
  const auto traces = trace_junctions(s, {2, 0}, 0.5, 200);
  REQUIRE(traces.size() == 2);
  std::size_t checked = 0;
  for (const JunctionTrace& tr : traces)
    for (std::size_t k = 0; k < tr.t_s.size(); ++k) {
      if (std::isfinite(tr.first_slip_s) && tr.t_s[k] >= tr.first_slip_s) break;
      const double A0 = s.experiment.junctions.area_m2[tr.junction];
      CHECK_THAT(tr.A_m2[k], WithinRel(p.law.area(A0, tr.f_N[k]), 1e-14));
      if (tr.f_N[k] > 0) CHECK(tr.A_m2[k] < A0);
      ++checked;
    }
  CHECK(checked > 20);
}

TEST_CASE("crowded and sparse junctions pair from the ends of the crowding order", "[report][pairs]") {
  const std::vector<double> crowding{5, 1, 9, 3, 7, 2, 8};
  const auto pairs = crowded_sparse_pairs({0, 1, 2, 3, 4, 5, 6}, crowding, 3);
  REQUIRE(pairs.size() == 3);
  CHECK(pairs[0].crowded == 2);
  CHECK(pairs[0].sparse == 1);
  CHECK(pairs[1].crowded == 6);
  CHECK(pairs[1].sparse == 5);
  CHECK(pairs[2].crowded == 4);
  CHECK(pairs[2].sparse == 3);
  CHECK(crowded_sparse_pairs({0, 1, 2}, crowding, 3).size() == 1);  // too few for more
}
