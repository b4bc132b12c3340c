// The parametric bootstrap around a certified optimum (fit_uncertainty.hpp, run_bootstrap).
#include <algorithm>
#include <cmath>
#include <string>

#include "batch/parallel_runner.hpp"
#include "fit/fit_problem.hpp"
#include "fit/fit_uncertainty.hpp"
#include "fit/objective.hpp"
#include "io/random.hpp"

namespace asperity::fit_detail {

namespace {

// The seed of one noise stream: draw d (1-based), the k-th experiment of the optimization,
// stream 0 (A(Q)) or 1 (Q(t)); independent streams from one base seed.
std::uint64_t stream_seed(std::uint64_t base, std::size_t d, std::size_t k, int stream) {
  return io::splitmix64(io::splitmix64(io::splitmix64(base) + d) + 2 * k + static_cast<std::size_t>(stream));
}

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// Draw d's fit spec: each experiment of the optimization measured as the model at the optimum
// plus Gaussian noise at the objective's own levels (objective.hpp: noise.area · Σ A0 on A,
// noise.force · max Q on Q(t)) times s, the root of the reduced chi-square: the noise the
// residuals show, as the Hessian's covariance 2 s² H⁻¹ takes it. Empty string, or why the draw
// cannot be made.
std::string synthetic_draw(const FitSpec& spec, const Optimization& o, std::size_t d, double s, FitSpec& draw) {
  draw = spec;
  for (std::size_t k = 0; k < o.best_runs.size(); ++k) {
    const ExperimentRun& er = o.best_runs[k];
    FitExperiment& fe = draw.experiments[er.experiment];
    if (er.measured && !er.measured->Q_N.empty()) {
      MeasuredCurve c = *er.measured;
      c.A_m2 = model_area_at(er.loading, er.obs.Q_s, er.obs.A_s, c.Q_N);
      if (!all_finite(c.A_m2)) return fe.name + ": the model's A(Q) at the optimum is not finite at a measured Q";
      io::Uniform01 u(stream_seed(spec.bootstrap_seed, d, k, 0));
      for (double& a : c.A_m2) a += s * spec.noise.area * er.obs.A0 * io::normal_quantile(u());
      fe.measured_override = std::move(c);
    }
    if (er.force && !er.force->t_s.empty()) {
      MeasuredForce f = *er.force;
      const double scale = s * spec.noise.force * *std::max_element(f.Q_N.begin(), f.Q_N.end());
      f.Q_N = model_force_at(er.series, f.t_s);
      if (!all_finite(f.Q_N)) return fe.name + ": the model's Q(t) at the optimum is not finite at a measured t";
      io::Uniform01 u(stream_seed(spec.bootstrap_seed, d, k, 1));
      for (double& q : f.Q_N) q += scale * io::normal_quantile(u());
      fe.force = std::move(f);
    }
  }
  return "";
}

}  // namespace

void run_bootstrap(const FitSpec& spec, const Problem& pb, Optimization& o) {
  const auto t0 = Clock::now();
  Bootstrap& bs = o.bootstrap;
  bs.draws.assign(static_cast<std::size_t>(spec.bootstrap_draws), {});
  const std::size_t n = o.variables.size();
  const double s = std::sqrt(o.uncertainty.reduced_chi2);
  if (!(s > 0 && std::isfinite(s))) {
    bs.failure = "no reduced chi-square to scale the noise by (" + o.uncertainty.failure + ")";
    bs.draws.clear();
    return;
  }
  for_each_nested(bs.draws.size(), [&](std::size_t i) {
    BootstrapDraw& bd = bs.draws[i];
    FitSpec draw;
    bd.failure = synthetic_draw(spec, o, i + 1, s, draw);
    if (!bd.failure.empty()) {
      bd.best.assign(n, Observables::nan);
      return;
    }
    Problem q = pb;
    q.spec = &draw;
    q.part = "bootstrap " + std::to_string(i + 1);
    q.log.clear();
    q.failure.clear();
    // From the optimum, where the draw's truth lies, with the error-bar refits' smaller step.
    bd = local_optimum(optimize(std::move(q), o.best, spec.initial_step * 0.25, /*polish_only=*/true));
  });
  std::vector<const BootstrapDraw*> ok;
  for (const BootstrapDraw& bd : bs.draws) {
    bs.evaluations += bd.evaluations;
    if (bd.failure.empty() && std::isfinite(bd.objective) && all_finite(bd.best)) ok.push_back(&bd);
  }
  bs.succeeded = static_cast<int>(ok.size());
  bs.wall_s = seconds_since(t0);
  if (ok.size() < 2) {
    bs.failure = std::to_string(ok.size()) + " of " + std::to_string(bs.draws.size()) +
                 " bootstrap refits succeeded: no spread to measure";
    for (const BootstrapDraw& bd : bs.draws)
      if (!bd.failure.empty()) {
        bs.failure += " (first failure: " + bd.failure + ")";
        break;
      }
    return;
  }
  bs.mean.assign(n, 0.0);
  bs.sigma.assign(n, 0.0);
  const auto m = static_cast<double>(ok.size());
  for (std::size_t v = 0; v < n; ++v) {
    for (const BootstrapDraw* bd : ok) bs.mean[v] += bd->best[v] / m;
    for (const BootstrapDraw* bd : ok) bs.sigma[v] += (bd->best[v] - bs.mean[v]) * (bd->best[v] - bs.mean[v]);
    bs.sigma[v] = std::sqrt(bs.sigma[v] / (m - 1));
  }
}

}  // namespace asperity::fit_detail
