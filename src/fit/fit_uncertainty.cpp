#include "fit/fit_uncertainty.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "batch/parallel_runner.hpp"
#include "fit/objective.hpp"
#include "io/numbers.hpp"
#include "scene/scene_keys.hpp"

namespace asperity::fit_detail {

namespace {

// Where the profile rises by `rise` above `f0` on each side of the optimum (linear between
// points); NaN where it does not within the span.
void profile_interval(ParameterProfile& pp, double f0, double rise, double x0) {
  const auto& pts = pp.points;
  auto crossing = [&](int from, int step) {
    double xa = x0, fa = f0;
    for (int i = from; i >= 0 && i < static_cast<int>(pts.size()); i += step) {
      const ProfilePoint& p = pts[static_cast<std::size_t>(i)];
      if (p.status != "ok" || !std::isfinite(p.objective)) return Observables::nan;
      if (p.objective - f0 >= rise) return xa + (f0 + rise - fa) / (p.objective - fa) * (p.value - xa);
      xa = p.value, fa = p.objective;
    }
    return Observables::nan;
  };
  std::size_t mid = 0;  // the point nearest factor 1
  for (std::size_t i = 0; i < pts.size(); ++i)
    if (std::abs(pts[i].factor - 1) < std::abs(pts[mid].factor - 1)) mid = i;
  const bool at_mid = std::abs(pts[mid].factor - 1) < 1e-12;
  const int left = static_cast<int>(mid) - (at_mid ? 1 : 0), right = static_cast<int>(mid) + (at_mid ? 1 : 0);
  double a = crossing(left, -1), b = crossing(right, +1);
  if (a > b) std::swap(a, b);
  pp.lo = a, pp.hi = b;
  // Least-squares parabola in d = value − x0 (scaled by the span; Eigen's QR).
  double span = 0;
  for (const ProfilePoint& p : pts) span = std::max(span, std::abs(p.value - x0));
  if (!(span > 0)) return;
  std::vector<const ProfilePoint*> ok;
  for (const ProfilePoint& p : pts)
    if (p.status == "ok" && std::isfinite(p.objective)) ok.push_back(&p);
  if (ok.size() < 3) return;
  Eigen::MatrixXd V(static_cast<Eigen::Index>(ok.size()), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(ok.size()));
  for (std::size_t r = 0; r < ok.size(); ++r) {
    const double d = (ok[r]->value - x0) / span;
    V.row(static_cast<Eigen::Index>(r)) << 1.0, d, d * d;
    y[static_cast<Eigen::Index>(r)] = ok[r]->objective - f0;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(V);
  if (qr.rank() < 3) return;
  const double c2 = qr.solve(y)[2] / (span * span);  // back to SI
  if (c2 > 0) pp.parabola_sigma = std::sqrt(rise / c2);
}

// The Hessian's evaluations: objective values at points of the scaled coordinates u ∈ [0, 1]ⁿ,
// in parallel and journaled (part "hessian", numbered on).
struct HessianPoints {
  const FitSpec& spec;
  const Problem& pb;
  const Optimization& o;
  int counter = 0;  // evaluations so far

  void eval(const std::vector<std::vector<double>>& us, std::vector<double>& fv, std::vector<std::string>& st) {
    const std::size_t n = o.variables.size();
    fv.assign(us.size(), Observables::nan);
    st.assign(us.size(), "");
    const int base = counter;
    counter += static_cast<int>(us.size());
    for_each_nested(us.size(), [&](std::size_t k) {
      std::vector<double> x(n);
      for (std::size_t v = 0; v < n; ++v) x[v] = parameter_value(spec.parameters[o.variables[v].parameter], us[k][v]);
      Problem qb = pb;
      qb.part = "hessian";
      const int index = base + static_cast<int>(k) + 1;
      const std::optional<Evaluation> ev = evaluate_journaled(qb, index, x);
      if (!ev) throw NotJournaled(not_journaled_text(qb, index, x));
      tick(qb, "hessian", ev->objective);
      fv[k] = ev->objective;
      st[k] = ev->status;
    });
  }
};

// The optimum in scaled coordinates u0, the first steps h (hessian_step relative) and dx/du; an
// empty string, or why there is no central difference.
std::string hessian_start(const FitSpec& spec, const Optimization& o, std::vector<double>& u0, std::vector<double>& h,
                          std::vector<double>& dxdu) {
  const std::size_t n = o.variables.size();
  u0.resize(n), h.resize(n), dxdu.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const FitParameter& p = spec.parameters[o.variables[i].parameter];
    u0[i] = parameter_coordinate(p, o.best[i]);
    if (p.log_scale) {
      h[i] = spec.hessian_step / std::log(p.hi / p.lo);
      dxdu[i] = o.best[i] * std::log(p.hi / p.lo);
    } else {
      h[i] = spec.hessian_step * std::max(std::abs(o.best[i]), 0.01 * (p.hi - p.lo)) / (p.hi - p.lo);
      dxdu[i] = p.hi - p.lo;
    }
    if (u0[i] - h[i] < 0 || u0[i] + h[i] > 1)
      return o.variables[i].label + " = " + io::format_significant(o.best[i]) + " is within one step (" +
             io::format_significant(spec.hessian_step) + " relative) of its bound: no central difference";
  }
  return "";
}

// Steps: from hessian_step, rescaled (up to 4 rounds) until each parameter's own central rise
// (f(+h) + f(−h))/2 − f0 is within [1, 16] s² (target 4 s²: about two conditional standard
// deviations): large enough above rounding, small enough to stay quadratic where the objective is
// sharp (epsilon moves every stick-slip event). An empty string, or why not.
std::string settle_steps(HessianPoints& hp, const std::vector<double>& u0, std::vector<double>& h, double f0,
                         double s2) {
  const std::size_t n = u0.size();
  const double target = 4 * s2;
  std::vector<bool> settled(n, false);
  for (int round = 0; round < 5; ++round) {
    std::vector<std::vector<double>> us;
    std::vector<std::size_t> who;
    for (std::size_t i = 0; i < n; ++i) {
      if (settled[i]) continue;
      for (const int sg : {-1, +1}) {
        std::vector<double> u = u0;
        u[i] += sg * h[i];
        us.push_back(u);
      }
      who.push_back(i);
    }
    if (who.empty()) break;
    std::vector<double> fv;
    std::vector<std::string> st;
    hp.eval(us, fv, st);
    for (std::size_t w = 0; w < who.size(); ++w) {
      const std::size_t i = who[w];
      if (st[2 * w] != "ok" || st[2 * w + 1] != "ok")
        return "hessian evaluation along " + hp.o.variables[i].label + ": " +
               (st[2 * w] != "ok" ? st[2 * w] : st[2 * w + 1]);
      const double rise = 0.5 * (fv[2 * w] + fv[2 * w + 1]) - f0;
      if (round == 4 || (rise >= target / 4 && rise <= target * 4)) {
        settled[i] = true;
        continue;
      }
      const double factor = rise > 0 ? std::clamp(std::sqrt(target / rise), 0.05, 20.0) : 10.0;
      h[i] = std::min(h[i] * factor, std::min(u0[i], 1 - u0[i]));
      if (!(h[i] > 0)) return hp.o.variables[i].label + " is at its bound: no central difference";
    }
  }
  return "";
}

// The Hessian in the scaled coordinates from ±h_i and (±h_i, ±h_j), i < j; an empty string, or
// which evaluation failed.
std::string hessian_at(HessianPoints& hp, const std::vector<double>& u0, const std::vector<double>& h, double f0,
                       Eigen::MatrixXd& H) {
  const std::size_t n = u0.size();
  struct Point {
    std::size_t i, j;
    int si, sj;
  };
  std::vector<Point> pts;
  for (std::size_t i = 0; i < n; ++i)
    for (const int si : {-1, +1}) pts.push_back({i, i, si, 0});
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      for (const int si : {-1, +1})
        for (const int sj : {-1, +1}) pts.push_back({i, j, si, sj});
  std::vector<std::vector<double>> us;
  for (const Point& pt : pts) {
    std::vector<double> u = u0;
    u[pt.i] += pt.si * h[pt.i];
    if (pt.sj != 0) u[pt.j] += pt.sj * h[pt.j];
    us.push_back(u);
  }
  std::vector<double> f;
  std::vector<std::string> status;
  hp.eval(us, f, status);
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (status[k] != "ok") return "hessian evaluation " + std::to_string(k + 1) + ": " + status[k];
  const auto N = static_cast<Eigen::Index>(n);
  H = Eigen::MatrixXd::Zero(N, N);
  std::size_t k = 0;
  for (Eigen::Index i = 0; i < N; ++i, k += 2) H(i, i) = (f[k] - 2 * f0 + f[k + 1]) / (h[i] * h[i]);
  for (Eigen::Index i = 0; i < N; ++i)
    for (Eigen::Index j = i + 1; j < N; ++j, k += 4)  // order: (−,−), (−,+), (+,−), (+,+)
      H(i, j) = H(j, i) = (f[k + 3] - f[k + 2] - f[k + 1] + f[k]) / (4 * h[i] * h[j]);
  return "";
}

}  // namespace

void run_profile(const FitSpec& spec, const Problem& pb, Optimization& o) {
  const auto t0 = Clock::now();
  const ProfileSettings& ps = spec.profile_settings;
  const std::vector<std::size_t> which = ps.parameters.empty() ? std::vector<std::size_t>{ps.parameter} : ps.parameters;
  const std::size_t m = static_cast<std::size_t>(ps.points);
  std::vector<ParameterProfile> profiles(which.size());
  for (std::size_t q = 0; q < which.size(); ++q) {
    profiles[q].parameter = which[q];
    profiles[q].points.resize(m);
  }
  for_each_nested(which.size() * m, [&](std::size_t flat) {
    const std::size_t q = flat / m, i = flat % m;
    const FitParameter& p = spec.parameters[which[q]];
    ProfilePoint& pt = profiles[q].points[i];
    pt.factor = 1.0 + ps.span * (2.0 * static_cast<double>(i) / static_cast<double>(m - 1) - 1.0);
    std::vector<double> x = o.best;
    bool inside = true;
    for (std::size_t j = 0; j < x.size(); ++j)
      if (o.variables[j].parameter == which[q]) {
        x[j] = o.best[j] * pt.factor;
        pt.value = x[j];
        inside = inside && x[j] >= p.lo && x[j] <= p.hi;
      }
    if (!inside) {
      pt.status = "outside the bounds";
      return;
    }
    Problem qb = pb;
    qb.part = "profile";
    const int index = static_cast<int>(flat) + 1;
    const std::optional<Evaluation> ev = evaluate_journaled(qb, index, x);
    if (!ev) throw NotJournaled(not_journaled_text(qb, index, x));
    tick(qb, "profile", ev->objective);
    pt.objective = ev->objective;
    pt.status = ev->status;
  });
  o.profiles = std::move(profiles);
  o.profile_parameter = o.profiles.front().parameter;
  o.profile = o.profiles.front().points;
  o.profile_wall_s = seconds_since(t0);
}

void run_uncertainty(const FitSpec& spec, const Problem& pb, Optimization& o) {
  const auto t0 = Clock::now();
  Uncertainty& un = o.uncertainty;
  un.step = spec.hessian_step;
  const std::size_t n = o.variables.size();
  for (const std::size_t e : o.experiments)
    un.residuals +=
        area_and_force_count(spec.experiments[e].scene.build(), spec.experiments[e], spec.noise, spec.force_score);
  const double f0 = o.objective;
  if (un.residuals <= static_cast<int>(n)) {
    un.failure = std::to_string(un.residuals) + " residuals for " + std::to_string(n) + " free variables";
    return;
  }
  un.reduced_chi2 = f0 / static_cast<double>(un.residuals - static_cast<int>(n));
  std::vector<double> u0, h, dxdu;
  if (un.failure = hessian_start(spec, o, u0, h, dxdu); !un.failure.empty()) return;
  HessianPoints hp{spec, pb, o};
  Eigen::MatrixXd H;
  un.failure = settle_steps(hp, u0, h, f0, un.reduced_chi2);
  if (un.failure.empty()) un.failure = hessian_at(hp, u0, h, f0, H);
  un.evaluations = hp.counter;
  if (!un.failure.empty()) return;
  const Eigen::LLT<Eigen::MatrixXd> llt(H);
  if (llt.info() != Eigen::Success) {
    std::string rows;
    for (Eigen::Index i = 0; i < H.rows(); ++i) {
      rows += i ? "; " : "";
      for (Eigen::Index j = 0; j < H.cols(); ++j) {
        if (j) rows += " ";  // (two appends: GCC 12's -Wrestrict misreads " " + string here)
        rows += io::format_significant(H(i, j));
      }
    }
    un.failure =
        "the Hessian of the objective at the optimum is not positive definite (a flat or unidentifiable direction, "
        "or the optimum is not a minimum on the step's scale): H = [" +
        rows + "] in the scaled coordinates";
    return;
  }
  const Eigen::MatrixXd inv = llt.solve(Eigen::MatrixXd::Identity(H.rows(), H.cols()));
  un.steps.resize(n);
  for (std::size_t i = 0; i < n; ++i) un.steps[i] = h[i] * std::abs(dxdu[i]) / std::abs(o.best[i]);
  un.sigma.resize(n);
  un.correlation.assign(n, std::vector<double>(n, 0.0));
  const auto I = [](std::size_t i) { return static_cast<Eigen::Index>(i); };
  for (std::size_t i = 0; i < n; ++i)
    un.sigma[i] = std::abs(dxdu[i]) * std::sqrt(2 * un.reduced_chi2 * inv(I(i), I(i)));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      un.correlation[i][j] = inv(I(i), I(j)) / std::sqrt(inv(I(i), I(i)) * inv(I(j), I(j)));
  un.computed = true;
  un.wall_s = seconds_since(t0);
  // The profiles' conditional intervals at the same rise s².
  for (ParameterProfile& pp : o.profiles)
    for (std::size_t v = 0; v < n; ++v)
      if (o.variables[v].parameter == pp.parameter && o.variables[v].experiment < 0)
        profile_interval(pp, f0, un.reduced_chi2, o.best[v]);
}

void run_refits(const FitSpec& spec, const FitOptions& options, Optimization& o, Counts& counts, const StopFlag& stop,
                std::atomic<int>& ticked) {
  const auto t0 = Clock::now();
  std::vector<ErrorBarRefit> refits;
  for (const auto& eb : spec.error_bars)
    for (const int sign : {-1, +1}) refits.push_back({{}, eb.key, eb.bar, sign});
  for_each_nested(refits.size(), [&](std::size_t i) {
    ErrorBarRefit& rf = refits[i];
    Problem q;
    q.spec = &spec;
    q.label = o.label;
    q.part = "refit " + rf.key + " " + (rf.sign < 0 ? "-1" : "+1");
    q.journal = options.journal;
    q.replay_only = options.replay_only;
    q.counts = &counts;
    q.stop = &stop;
    q.user_term = &options.user_term;
    q.on_evaluation = &options.on_evaluation;
    q.ticked = &ticked;
    q.exps = o.experiments;
    q.vars = o.variables;
    for (const std::size_t e : o.experiments) {
      const double nominal = scene_value(spec.experiments[e].scene.build(), rf.key);
      q.extra.push_back({{rf.key, nominal + rf.sign * rf.bar}});
    }
    // Start at the optimum with a smaller first step: the shift moves it little.
    static_cast<LocalOptimum&>(rf) =
        local_optimum(optimize(std::move(q), o.best, spec.initial_step * 0.25, /*polish_only=*/true));
  });
  o.refits = std::move(refits);
  o.refits_wall_s = seconds_since(t0);
}

}  // namespace asperity::fit_detail
