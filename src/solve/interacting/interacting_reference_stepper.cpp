#include "solve/interacting/interacting_reference_stepper.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "physics/interface_law.hpp"
#include "solve/core/run_limits.hpp"

namespace asperity {

InteractingReferenceStepper::InteractingReferenceStepper(const Problem& problem)
    : p_(problem),
      scheme_(problem),
      C_(interaction_matrix(problem)),
      forces_(problem, C_),
      J_(problem.A0, problem.law),
      deadline_(wall_deadline(problem.limits)) {}

void InteractingReferenceStepper::advance(RunObserver& out) {
  const ContactLaw& law = p_.law;
  const AreaLaw area_law = p_.area_law;
  JunctionState& J = J_;
  const std::size_t N = J.size();
  const double X1 = scheme_.next_X();
  const bool slow = scheme_.slow();

  // (1) Repinning junctions hold their force this step; (2)–(3) solve the pinned, slip, repeat.
  std::vector<std::uint8_t> repinning(N, 0), solve(N, 0);
  bool any_repin = false;
  for (std::size_t i = 0; i < N; ++i) {
    if (!J.pinned[i] && slow) repinning[i] = 1, any_repin = true;
    solve[i] = J.pinned[i];
  }
  std::int64_t slips = 0, force_evals = 0;
  for (int round = 0;; ++round) {
    if (round > 0 && std::chrono::steady_clock::now() >= deadline_) throw WallTimeReached();
    force_evals += forces_.solve(J, solve, X1, deadline_);
    std::int64_t new_slips = 0;
    for (std::size_t i = 0; i < N; ++i)
      if (solve[i] && starts_to_slip(J.force[i], J.f_s[i])) {
        solve[i] = 0;
        J.pinned[i] = 0;
        J.intact[i] = 0;
        J.force[i] = slipping_force(law, area_law, J.A0[i], J.f_s[i]);
        if (area_law == AreaLaw::always) J.set_contact(i, contact_at_force(law, J.A0[i], J.force[i]));
        ++new_slips;
      }
    slips += new_slips;
    if (new_slips == 0) break;
  }
  // (4) Anchors of the repinned junctions: X − x_i = f_i/k_i + Σ_{j≠i} C_ij f_j.
  for (std::size_t i = 0; i < N; ++i)
    if (repinning[i]) {
      double u = 0;
      for (std::size_t j = 0; j < N; ++j) u += C_(i, j) * J.force[j];
      J.anchor[i] = repin_anchor(X1, J.force[i], J.k[i]) - u;
      J.pinned[i] = 1;
    }

  scheme_.complete(out, junction_totals(J, law.sigma, &max_ratio_), slips, any_repin, force_evals);
}

}  // namespace asperity
