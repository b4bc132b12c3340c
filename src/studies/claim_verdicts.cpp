#include "studies/claim_verdicts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace asperity {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// Largest of the values; NaN as soon as one is NaN (an unknown difference is not a small one).
double max_of(std::initializer_list<double> xs) {
  double m = 0;
  for (double x : xs) {
    if (std::isnan(x)) return Observables::nan;
    m = std::max(m, x);
  }
  return m;
}

Verdict combine_all(const std::vector<Verdict>& v) { return combine(std::span<const Verdict>(v)); }

// The runs of a load could show stick-slip: they went on after a confirmed peak.
bool could_show_stick_slip(const LoadObservables& l, const Observables& o) { return l.past_first_peak && o.peak_found; }

}  // namespace

const char* verdict_text(Verdict v) {
  switch (v) {
    case Verdict::reproduced:
      return "Reproduced";
    case Verdict::not_reproduced:
      return "Not reproduced";
    case Verdict::no_evidence:
      return "No evidence";
  }
  return "No evidence";
}

Verdict combine(std::span<const Verdict> per_load) {
  if (per_load.empty()) return Verdict::no_evidence;
  if (std::find(per_load.begin(), per_load.end(), Verdict::not_reproduced) != per_load.end())
    return Verdict::not_reproduced;
  if (std::find(per_load.begin(), per_load.end(), Verdict::no_evidence) != per_load.end()) return Verdict::no_evidence;
  return Verdict::reproduced;
}

double stick_slip_difference(const Observables& a, const Observables& b) {
  const bool sa = a.ss_cycles > 0, sb = b.ss_cycles > 0;
  if (!sa && !sb) return 0;
  if (sa != sb) return inf;
  return max_of({rel(a.ss_drop, b.ss_drop), rel(a.ss_period, b.ss_period)});
}

Verdict claim1_dt(const ClaimObservables& c, const ClaimRules& r) {
  // Mid loads: all but the smallest and the largest; none with fewer than three loads.
  std::vector<Verdict> v;
  for (std::size_t i = 1; i + 1 < c.loads.size(); ++i) {
    const double dt = c.loads[i].base.dt;
    v.push_back(std::isnan(dt)                 ? Verdict::no_evidence
                : dt > r.dt_lo && dt < r.dt_hi ? Verdict::reproduced
                                               : Verdict::not_reproduced);
  }
  return combine_all(v);
}

Verdict claim2_stick_slip(const LoadObservables& l) {
  if (l.base_eta != 100) return Verdict::no_evidence;  // the claim is about η = 100
  if (l.base.ss_cycles > 0) return Verdict::reproduced;
  return could_show_stick_slip(l, l.base) ? Verdict::not_reproduced : Verdict::no_evidence;
}

Verdict claim2_stick_slip(const ClaimObservables& c) {
  std::vector<Verdict> v;
  for (const auto& l : c.loads) v.push_back(claim2_stick_slip(l));
  return combine_all(v);
}

EtaComparison claim3_eta50_vs_base(const ClaimObservables& c, const ClaimRules& r) {
  EtaComparison out;
  out.loading_diff = 0;
  out.stick_slip_diff = 0;
  bool missing = c.loads.empty();
  for (const auto& l : c.loads) {
    const Observables* o50 = nullptr;
    for (const auto& [eta, o] : l.eta_scan)
      if (eta == 50 && o) o50 = &*o;
    if (!o50 || l.base_eta != 100) {  // the claim compares η = 50 with the paper's η = 100
      missing = true;
      continue;
    }
    const Observables& b = l.base;
    const double dl =
        max_of({rel(o50->Q_s, b.Q_s), rel(o50->A_s, b.A_s), rel(o50->t_peak, b.t_peak), rel(o50->alpha, b.alpha)});
    out.loading_diff =
        std::isnan(dl) || std::isnan(out.loading_diff) ? Observables::nan : std::max(out.loading_diff, dl);
    // Stick-slip compared only where both runs could show it.
    if (could_show_stick_slip(l, b) && could_show_stick_slip(l, *o50))
      out.stick_slip_diff = std::max(out.stick_slip_diff, stick_slip_difference(*o50, b));
    else
      missing = true;
  }
  if (!missing && !std::isnan(out.loading_diff))
    out.verdict = out.loading_diff < r.same_loading && out.stick_slip_diff < r.same_stick_slip
                      ? Verdict::reproduced
                      : Verdict::not_reproduced;
  else if ((out.loading_diff >= r.same_loading) || (out.stick_slip_diff >= r.same_stick_slip))
    out.verdict = Verdict::not_reproduced;  // the runs that exist already contradict it
  return out;
}

VanishBracket claim3_vanish_bracket(const LoadObservables& l, const ClaimRules& r) {
  VanishBracket out;
  std::vector<std::pair<double, const Observables*>> scan{{l.base_eta, &l.base}};
  bool missing = false;
  for (const auto& [eta, o] : l.eta_scan) {
    if (o)
      scan.emplace_back(eta, &*o);
    else
      missing = true;
  }
  std::sort(scan.begin(), scan.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  double last_with = -inf;
  for (const auto& [eta, o] : scan)
    if (o->ss_cycles > 0) last_with = eta;
  double first_without = inf;
  for (const auto& [eta, o] : scan)
    if (eta > last_with && o->ss_cycles == 0) {
      first_without = eta;
      break;
    }
  out.last_with = last_with;
  out.first_without = first_without;
  bool could = true;
  for (const auto& [eta, o] : scan) could = could && could_show_stick_slip(l, *o);
  if (missing || !could) return out;  // no_evidence
  out.verdict =
      last_with < r.vanish_max && first_without >= r.vanish_min ? Verdict::reproduced : Verdict::not_reproduced;
  return out;
}

MaxDifference claim4_c_min(const ClaimObservables& c, const ClaimRules& r) {
  MaxDifference out;
  out.diff = 0;
  bool missing = c.loads.empty();
  for (const auto& l : c.loads) {
    if (!l.c_min_low) {
      missing = true;
      continue;
    }
    const Observables& o = *l.c_min_low;
    const Observables& b = l.base;
    const double d =
        max_of({rel(o.Q_s, b.Q_s), rel(o.A_s, b.A_s), rel(o.t_peak, b.t_peak), stick_slip_difference(o, b)});
    out.diff = std::isnan(d) || std::isnan(out.diff) ? Observables::nan : std::max(out.diff, d);
  }
  if (out.diff >= r.same_c_min)
    out.verdict = Verdict::not_reproduced;
  else if (!missing && !std::isnan(out.diff))
    out.verdict = Verdict::reproduced;
  return out;
}

Claim5Verdicts claim5_calibrated(const LoadObservables& l, const ClaimRules& r) {
  Claim5Verdicts out;
  auto within = [&](double model, double measured) {
    if (std::isnan(model) || std::isnan(measured)) return Verdict::no_evidence;
    return rel(model, measured) < r.match ? Verdict::reproduced : Verdict::not_reproduced;
  };
  const AreaComparison& shown = l.calibrated ? *l.calibrated : l.at_scene_alpha_b;
  if (l.calibrated) {
    out.decay = within(shown.decay_model, shown.decay_measured);
    out.slope = within(shown.slope_model, shown.slope_measured);
  }
  if (!std::isnan(shown.n_model) && !std::isnan(shown.n_measured))
    out.shape = shown.n_model < r.quasi_linear_n && shown.n_measured > r.quadratic_n ? Verdict::reproduced
                                                                                     : Verdict::not_reproduced;
  return out;
}

Claim5Verdicts claim5_calibrated(const ClaimObservables& c, const ClaimRules& r) {
  std::vector<Verdict> d, s, n;
  for (const auto& l : c.loads) {
    const Claim5Verdicts v = claim5_calibrated(l, r);
    d.push_back(v.decay);
    s.push_back(v.slope);
    n.push_back(v.shape);
  }
  return {combine_all(d), combine_all(s), combine_all(n)};
}

Verdict claim6_equal_areas(const LoadObservables& l, const ClaimRules& r) {
  // "Up to macroscopic sliding": the fit is over the loading branch, which needs the peak.
  if (!l.equal_areas || !l.equal_areas->peak_found || std::isnan(l.equal_areas->alpha_R2)) return Verdict::no_evidence;
  return l.equal_areas->alpha_R2 > r.quadratic_R2 ? Verdict::reproduced : Verdict::not_reproduced;
}

Verdict claim7_forces(const ClaimObservables& c) {
  // Needs the reference solver's window with slips in it (it alone measures f/(σA)).
  if (!c.reference || c.reference->slips == 0 || std::isnan(c.reference->max_f_over_sigmaA) ||
      std::isnan(c.reference->max_f_over_sigma_exp_A))
    return Verdict::no_evidence;
  return c.reference->max_f_over_sigmaA <= 1.0 && c.reference->max_f_over_sigma_exp_A > 1.0 ? Verdict::reproduced
                                                                                            : Verdict::not_reproduced;
}

Verdict claim8_shape_robust(const LoadObservables& l, const ClaimRules& r) {
  if (!l.circular || !l.area_law_always) return Verdict::no_evidence;
  const double n[] = {l.base.shape_exponent, l.circular->shape_exponent, l.area_law_always->shape_exponent};
  for (double x : n)
    if (std::isnan(x)) return Verdict::no_evidence;
  for (double x : n)
    if (!(x < r.quasi_linear_n)) return Verdict::not_reproduced;
  return Verdict::reproduced;
}

}  // namespace asperity
