#include "studies/interaction_verdicts.hpp"

#include <algorithm>

namespace asperity::interaction_detail {

Tally tally_rows(const std::vector<StudyRow>& rows) {
  Tally t;
  for (const auto& r : rows) {
    if (!r.inter.ran || !std::isfinite(r.inter.shape.residual_rms)) continue;
    ++t.ran;
    if (!r.inter.shape.residual_exceeds_noise()) ++t.quadratic;
    if (r.indep.ran && std::isfinite(r.indep.shape.residual_rms)) {
      if (!r.indep.shape.residual_exceeds_noise()) ++t.indep_quadratic;
      const double diff = r.indep.shape.residual_rms - r.inter.shape.residual_rms;
      const double spread = 2 * (r.indep.shape.residual_rms_sd + r.inter.shape.residual_rms_sd);
      if (diff > spread)
        ++t.closer;
      else if (-diff > spread)
        ++t.farther;
      else
        ++t.undecided;
    }
    if (r.indep.ran && std::isfinite(r.indep.obs.shape_exponent) && std::isfinite(r.inter.obs.shape_exponent))
      t.dn_sum += r.inter.obs.shape_exponent - r.indep.obs.shape_exponent, ++t.dn_count;
  }
  return t;
}

std::string verdict_of(const Tally& t) {
  const std::string of = " of " + std::to_string(t.ran) + " loads";
  if (t.ran == 0) return "No evidence (no calibrated interacting run with a measured curve)";
  if (t.quadratic == t.ran) return "Quadratic within the noise at every load (" + std::to_string(t.ran) + of + ")";
  return "Not quadratic: the interacting A(Q) is within the measurement noise of the measured curve at " +
         std::to_string(t.quadratic) + of;
}

bool q_within(const JointSide& s) { return s.force.within_noise(); }
bool a_within(const JointSide& s) { return std::isfinite(s.shape.residual_rms) && !s.shape.residual_exceeds_noise(); }

JointTally tally_joint(const std::vector<JointRow>& rows) {
  JointTally t;
  for (const JointRow& r : rows) {
    if (r.indep.ran) ++t.indep_ran, t.indep_q += q_within(r.indep), t.indep_a += a_within(r.indep);
    if (r.inter.ran) ++t.inter_ran, t.inter_q += q_within(r.inter), t.inter_a += a_within(r.inter);
  }
  return t;
}

std::string joint_verdict(const JointTally& t, std::size_t loads) {
  if (t.indep_ran == 0 && t.inter_ran == 0)
    return "Joint calibration of (α_b, ε, η) against A(Q) and Q(t): no evidence (no joint calibration found).";
  std::string v =
      "**Joint calibration of (α_b, ε, η) against A(Q) and Q(t): the measured Q(t) is matched within its noise by "
      "the independent model at " +
      std::to_string(t.indep_q) + " of " + std::to_string(t.indep_ran) +
      " calibrated loads and by the interacting model at " + std::to_string(t.inter_q) + " of " +
      std::to_string(t.inter_ran) + "; the measured A(Q) by the independent model at " + std::to_string(t.indep_a) +
      " of " + std::to_string(t.indep_ran) + " and by the interacting model at " + std::to_string(t.inter_a) + " of " +
      std::to_string(t.inter_ran) + ".** ";
  const int missing = static_cast<int>(loads) - std::min(t.indep_ran, t.inter_ran);
  if (missing > 0) v += "Loads without a joint calibration of a model read \"no evidence\" (table). ";
  // The stand-ins cannot decide between the models, so no comparison between them is drawn here.
  v += "**No verdict between the models is drawn from these fits**: the stand-in Q(t) is the independent model's own "
       "at the paper's parameters plus noise, so any comparison on it favours that model by construction, and the "
       "stand-in A(Q) is a prescribed parabola that neither model makes. What the joint method can tell apart is "
       "shown by model recovery on synthetic experiments of each model (docs/calibration.md, \"Synthetic experiments "
       "and model recovery\").";
  return v;
}

}  // namespace asperity::interaction_detail
