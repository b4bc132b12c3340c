// Each junction changes state at most once per step (pinned → slipping, or slipping → pinned),
// as the paper's scan does.
#include "solve/reference/reference_stepper.hpp"

#include <omp.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "physics/interface_law.hpp"

namespace asperity {

ReferenceStepper::ReferenceStepper(const Problem& problem)
    : p_(problem), scheme_(problem), J_(problem.A0, problem.law), team_(omp_get_max_threads(), 256) {}

void ReferenceStepper::advance(RunObserver& out) {
  const ContactLaw& law = p_.law;
  const AreaLaw area_law = p_.area_law;
  const bool always = area_law == AreaLaw::always;
  JunctionState& J = J_;
  const std::size_t N = J.size();
  const double X1 = scheme_.next_X();
  const bool slow = scheme_.slow();
  std::int64_t slips = 0;
  bool any_repin = false;
  const AdaptiveTeam::Region region(team_, static_cast<double>(N));
  const int threads = region.threads();
#pragma omp parallel for schedule(static) reduction(+ : slips) reduction(|| : any_repin) num_threads(threads) if (threads > 1)
  for (std::size_t i = 0; i < N; ++i) {
    double f;
    if (J.pinned[i]) {
      if (area_follows_force(area_law, J.intact[i])) {
        f = law.solve_pinned_force(J.A0[i], X1 - J.anchor[i]);
        J.set_contact(i, contact_at_force(law, J.A0[i], f));
      } else {
        f = pinned_force(J.k[i], X1, J.anchor[i]);
      }
      if (starts_to_slip(f, J.f_s[i])) {
        J.pinned[i] = 0;
        J.intact[i] = 0;
        f = slipping_force(law, area_law, J.A0[i], J.f_s[i]);
        if (always) J.set_contact(i, contact_at_force(law, J.A0[i], f));
        ++slips;
      }
    } else {
      f = J.force[i];
      if (slow) {  // repins with no force jump
        J.pinned[i] = 1;
        J.anchor[i] = repin_anchor(X1, f, J.k[i]);
        any_repin = true;
      }
    }
    J.force[i] = f;
  }
  scheme_.complete(out, junction_totals(J, law.sigma, &max_ratio_), slips, any_repin, 1);
}

}  // namespace asperity
