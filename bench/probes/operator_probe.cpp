// Probe (ASPERITY_PROBES builds it): the chord solver over two pinned operators side by side, the
// dense G (PinnedCompliance) and G applied by CG with the precorrected FFT product
// (krylov_operator.hpp), on `bench interacting`'s populations (the STAND-IN P4.00N's areas
// repeated to N). The dense solver writes a script of slips: from half the first slip, the next
// crossing predicted at first order, solved there, its most loaded junction slipped, `slips`
// times. Both solvers follow that script; printed: the wall time of each (solves and slips), the
// ratio, the Krylov operator's FFT products per solve, and its largest force difference from the
// dense solve at every step, in units of the slip force. Build against a Release build in build/
// and run from the repository root:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build operator_probe
//   OMP_NUM_THREADS=1 build/operator_probe 1200 [slips [interaction_tolerance]]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "krylov_operator.hpp"
#include "physics/interface_law.hpp"
#include "probe_population.hpp"
#include "solve/core/junction_state.hpp"
#include "solve/interacting/chord_solver_impl.hpp"
#include "solve/interacting/pinned_compliance.hpp"

using namespace asperity;

namespace {

struct Step {
  double X_before, X;  // the solve after the last slip, and the crossing
  std::size_t junction;
  double f_slip, area;
  std::vector<double> f;  // the dense solve's forces at X, by junction (slipping: 0)
};

std::vector<double> by_junction(const PinnedCompliance& P, const ForceNode& n, std::size_t N) {
  std::vector<double> f(N, 0.0);
  for (std::size_t q = 0; q < P.size(); ++q) f[P.junction(q)] = n.f[q];
  return f;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t N = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1200;
  const int slips = argc > 2 ? std::atoi(argv[2]) : 20;
  Scene s = load_scene("scenes/paper/P4.00N.yaml");
  const ProbePopulation pop = probe_population(N);
  s.experiment.junctions.area_m2 = pop.area_m2;
  s.experiment.junctions.x_m = pop.x_m;
  s.experiment.junctions.y_m = pop.y_m;
  s.model.interactions = Interactions::elastic;
  if (argc > 3) s.solver.interaction_tolerance = std::atof(argv[3]);
  const Problem p = make_problem(s);
  const JunctionState J(p.A0, p.law);

  // The dense solver writes the script.
  auto t0 = ProbeClock::now();
  ChordSolver<PinnedCompliance> dense(p, J, true, PinnedCompliance::kSingleFrom);
  const double dense_setup = seconds_since(t0);
  std::vector<Step> script;
  t0 = ProbeClock::now();
  ForceNode node = dense.solve(1e-9);
  double X = HUGE_VAL;
  for (std::size_t q = 0; q < dense.pinned().size(); ++q) X = std::min(X, 1e-9 * dense.threshold(q) / node.f[q]);
  X *= 0.5;
  for (int k = 0; k < slips; ++k) {
    const double X_before = X;
    node = dense.solve(X);
    double next = HUGE_VAL;  // the first crossing, first order
    for (std::size_t q = 0; q < dense.pinned().size(); ++q)
      if (node.a[q] > 0) next = std::min(next, X + (dense.threshold(q) - node.f[q]) / node.a[q]);
    X = std::max(X, next);
    node = dense.solve(X);
    std::size_t worst = 0;
    for (std::size_t q = 1; q < dense.pinned().size(); ++q)
      if (node.f[q] / dense.threshold(q) > node.f[worst] / dense.threshold(worst)) worst = q;
    const std::size_t i = dense.pinned().junction(worst);
    Step st{X_before,
            X,
            i,
            slipping_force(p.law, p.area_law, J.A0[i], J.f_s[i]),
            contact_at_first_slip(p.law, J.A0[i]).area_m2,
            by_junction(dense.pinned(), node, N)};
    dense.slip(worst, st.f_slip, st.area, X);
    script.push_back(st);
  }
  const double dense_s = seconds_since(t0);

  // The Krylov operator follows it.
  t0 = ProbeClock::now();
  ChordSolver<KrylovPinnedOperator> krylov(p, J, true, 0);
  const double krylov_setup = seconds_since(t0);
  const std::int64_t setup_products = krylov.pinned().products();
  double worst_error = 0;
  t0 = ProbeClock::now();
  int solves = 0;
  for (const Step& st : script) {
    krylov.solve(st.X_before);  // after the last slip, as the dense run did
    const ForceNode n = krylov.solve(st.X);
    solves += 2;
    for (std::size_t q = 0; q < krylov.pinned().size(); ++q) {
      const std::size_t i = krylov.pinned().junction(q);
      worst_error = std::max(worst_error, std::abs(n.f[q] - st.f[i]) / krylov.threshold(q));
    }
    krylov.slip(krylov.pinned().position(st.junction), st.f_slip, st.area, st.X);
  }
  const double krylov_s = seconds_since(t0);
  std::printf(
      "N %zu slips %d tol %g: dense %.4f s (set-up %.3f s, %lld chord passes), krylov %.4f s (set-up %.3f s, "
      "%lld chord passes), ratio %.2fx; FFT products %.1f per solve; largest force difference %.3g of the slip "
      "force\n",
      N, slips, p.solver.interaction_tolerance, dense_s, dense_setup, (long long)dense.iterations(), krylov_s,
      krylov_setup, (long long)krylov.iterations(), krylov_s / dense_s,
      double(krylov.pinned().products() - setup_products) / solves, worst_error);
}
