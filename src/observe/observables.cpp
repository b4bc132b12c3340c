#include "observe/observables.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "observe/quadratic_fit.hpp"
#include "observe/stick_slip.hpp"

namespace asperity {

namespace {

#define REAL(F, UNIT)                                                                                            \
  ObservableField {                                                                                              \
#F, UNIT, ObservableKind::real, [](const Observables& o) { return static_cast<double>(o.F); }, nullptr, true \
  }
#define COUNT(F)                                                                                                \
  ObservableField {                                                                                             \
#F, "", ObservableKind::count, [](const Observables& o) { return static_cast<double>(o.F); }, nullptr, true \
  }
const std::vector<ObservableField> kFields{
    COUNT(N),
    REAL(A0, "m^2"),
    REAL(K0, "N/m"),
    REAL(T0, "s"),
    REAL(dt, "s"),
    REAL(Q_s, "N"),
    REAL(A_s, "m^2"),
    REAL(t_peak, "s"),
    ObservableField{"peak_found", "", ObservableKind::flag,
                    [](const Observables& o) { return o.peak_found ? 1.0 : 0.0; }, nullptr, true},
    ObservableField{"peak_rule", "", ObservableKind::label, nullptr,
                    [](const Observables& o) { return to_string(o.peak_rule); }, false},
    REAL(alpha, "m^2/N^2"),
    REAL(alpha_R2, ""),
    COUNT(alpha_points),
    REAL(shape_exponent, ""),
    REAL(shape_prefactor, "m^2/N^n"),
    REAL(area_drop_fraction, ""),
    REAL(alpha_measured, "m^2/N^2"),
    REAL(alpha_measured_R2, ""),
    REAL(shape_exponent_measured, ""),
    COUNT(ss_cycles),
    REAL(ss_drop, "N"),
    REAL(ss_period, "s"),
    COUNT(n_peaks),
    REAL(max_f_over_sigmaA, ""),
    REAL(max_f_over_sigma_exp_A, ""),
    REAL(t_end, "s"),
    COUNT(steps),
    COUNT(rejected),
    COUNT(force_evals),
    COUNT(slips),
    COUNT(repins),
    ObservableField{"wall_s", "s", ObservableKind::real, [](const Observables& o) { return o.wall_s; }, nullptr, false},
};
#undef REAL
#undef COUNT

}  // namespace

const std::vector<ObservableField>& observable_fields() { return kFields; }

const ObservableField& observable_field(const std::string& name) {
  for (const ObservableField& f : kFields)
    if (name == f.name) return f;
  throw std::invalid_argument("no observable named " + name);
}

std::string observable_text(const ObservableField& f, const Observables& o, std::string (*real)(double)) {
  switch (f.kind) {
    case ObservableKind::real:
      return real(f.value(o));
    case ObservableKind::count:
      return std::to_string(static_cast<long long>(f.value(o)));
    case ObservableKind::flag:
      return f.value(o) != 0 ? "true" : "false";
    case ObservableKind::label:
      return f.label(o);
  }
  return "";
}

Observables summarize(const Scene& scene, const RunInfo& info, const Recorder& rec, double wall_s, int ss_cycles_max) {
  Observables o;
  o.N = info.N;
  o.A0 = info.A0;
  o.K0 = info.K0;
  o.T0 = info.T0;
  o.dt = info.dt;

  const auto& peaks = rec.peaks();
  const FirstPeak first = rec.first_peak();
  o.peak_found = first.found();
  o.peak_rule = first.rule;
  o.n_peaks = peaks.size();
  if (std::isfinite(first.max.Q)) {
    o.Q_s = first.max.Q;
    o.A_s = first.max.A;
    o.t_peak = first.max.t;
    o.area_drop_fraction = 1.0 - o.A_s / o.A0;
  }

  // Loading branch: the Recorder already cut it at a confirmed peak; otherwise cut it at the
  // peak found (a run that ends while still loading keeps all of it).
  const std::vector<Sample>* branch = &rec.loading_branch();
  std::vector<Sample> cut;
  if (peaks.empty() && std::isfinite(o.t_peak)) {
    for (const auto& s : *branch)
      if (s.t <= o.t_peak) cut.push_back(s);
    branch = &cut;
  }
  const QuadraticFit q = fit_quadratic_area(*branch, info.A0);
  o.alpha = q.alpha;
  o.alpha_R2 = q.R2;
  o.alpha_points = q.n_points;
  const ShapeIndex sh = fit_power_law(*branch, info.A0);
  o.shape_exponent = sh.n;
  o.shape_prefactor = sh.c;

  if (const auto& m = scene.experiment.measured) {
    const QuadraticFit qm = fit_quadratic_area(*m, info.A0);
    o.alpha_measured = qm.alpha;
    o.alpha_measured_R2 = qm.R2;
    o.shape_exponent_measured = fit_power_law(*m, info.A0).n;
  }

  const StickSlipStats ss = stick_slip_stats(peaks, ss_cycles_max);
  o.ss_cycles = ss.n_cycles;
  o.ss_drop = ss.mean_drop;
  o.ss_period = ss.mean_period;

  o.max_f_over_sigmaA = info.max_f_over_sigmaA;
  o.max_f_over_sigma_exp_A = info.max_f_over_sigma_exp_A;
  o.t_end = info.t_end;
  o.steps = info.stats.steps;
  o.rejected = info.stats.rejected;
  o.force_evals = info.stats.force_evals;
  o.slips = info.stats.slips;
  o.repins = info.stats.repins;
  o.wall_s = wall_s;
  return o;
}

}  // namespace asperity
