// The paper's Appendix 1, exactly (MODEL.md §3): velocity Verlet at fixed dt = T0/C_t, the
// damping term of γ(t+dt) taken at Ẋ(t) (the latest known velocity), forces at X(t+dt),
// never-slipped junctions by bisection, t = n·dt. Each junction changes state at most once
// per step (pinned → slipping, or slipping → pinned), as the paper's scan does.
#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "solve/integrate.hpp"
#include "solve/junction_state.hpp"

namespace asperity {

double reference_spectral_radius(double omega_dt, double eta_dt) {
  // Variables (X, h V, h² γ) for X'' = −ω² X − η Ẋ; the same map as the step below.
  const double a = omega_dt * omega_dt, b = eta_dt;
  // Eigen's eigensolver does not return on a matrix with inf or NaN (an absurd dt).
  if (!std::isfinite(a) || !std::isfinite(b)) return std::numeric_limits<double>::infinity();
  Eigen::Matrix3d m;
  // x1 = x + u + g/2;  g1 = −a x1 − b u;  u1 = u + (g + g1)/2
  m << 1, 1, 0.5,                           // x1
      -0.5 * a, 1 - 0.5 * a - 0.5 * b, 0.5 - 0.25 * a,  // u1
      -a, -a - b, -0.5 * a;                 // g1
  return m.eigenvalues().cwiseAbs().maxCoeff();
}

RunInfo initial_info(const Scene& scene) {
  const auto& e = scene.experiment;
  const ContactLaw law = make_contact_law(e, scene.model);
  RunInfo info;
  info.N = e.junctions.size();
  for (double a : e.junctions.area_m2) {
    info.A0 += a;
    info.K0 += law.stiffness(a, a);
  }
  info.T0 = 2.0 * M_PI / std::sqrt(info.K0 / e.mass_kg);
  info.dt = info.T0 / scene.solver.Ct;
  return info;
}

RunInfo integrate_reference(const Scene& scene, Recorder& rec, const RunLimits& limits) {
  const auto& e = scene.experiment;
  const auto& m = scene.model;
  const ContactLaw law = make_contact_law(e, m);
  const bool always = m.area_law == AreaLaw::always;
  RunInfo info = initial_info(scene);
  const double dt = info.dt, M = e.mass_kg, kL = e.k_L, v = e.v;
  const double v_repin = m.c_min * v;
  {
    const double rho = reference_spectral_radius(std::sqrt((info.K0 + kL) / M) * dt, m.eta * dt);
    if (rho > 1.0 + 1e-12) {
      char msg[200];
      std::snprintf(msg, sizeof msg,
                    "reference step unstable: spectral radius %.6g > 1 at dt = %.6g s (raise solver.Ct or lower model.eta)",
                    rho, dt);
      throw SolverError(msg);
    }
  }
  JunctionState J(e.junctions.area_m2, law);
  const std::size_t N = J.size();
  const auto n_end = static_cast<std::int64_t>(std::ceil(scene.stop.time / dt - 1e-9));

  double X = 0, V = 0, gamma = 0, A_sum = info.A0;
  std::int64_t n_slipping = 0, n_intact = static_cast<std::int64_t>(N);
  auto Q_at = [&](std::int64_t n, double Xn) { return kL * (v * (static_cast<double>(n) * dt) - Xn); };
  auto emit_samples = [&](std::int64_t n) {
    const double t = static_cast<double>(n) * dt;
    // The sample due at time ts is taken at the first step with t ≥ ts (t = n·dt exactly).
    while (rec.next_sample_time() <= t + 1e-9 * dt) rec.sample({t, X, V, Q_at(n, X), A_sum, n_slipping, n_intact});
  };
  emit_samples(0);

  double prevQ = 0, prevA = info.A0, prevV = 0, prevt = 0;
  double max_ratio = 0, max_ratio_exp = 0;
  std::int64_t n = 0;
  LimitGuard guard(limits);
  for (n = 1; n <= n_end && !rec.done(); ++n) {
    if ((info.stopped_by = guard.check(info.stats.slips)) != LimitHit::none) break;
    const double t = static_cast<double>(n) * dt;
    const double X1 = X + dt * V + 0.5 * dt * dt * gamma;
    const bool slow = std::abs(V) < v_repin;  // |Ẋ(t)|: the latest known velocity
    std::int64_t slips = 0;
    bool any_repin = false;
    // Fork only when the junctions outweigh the fork-join cost (~µs per step): at N = 60 two
    // threads were 8× slower than one (bench report).
#pragma omp parallel for schedule(static) reduction(+ : slips) reduction(|| : any_repin) if (N >= 256)
    for (std::size_t i = 0; i < N; ++i) {
      double f;
      if (J.pinned[i]) {
        if (J.intact[i] || always) {
          f = law.solve_pinned_force(J.A0[i], X1 - J.anchor[i]);
          J.area[i] = law.area(J.A0[i], f);
          J.k[i] = law.stiffness(J.A0[i], J.area[i]);
          J.f_s[i] = law.sigma * J.area[i];
        } else {
          f = J.k[i] * (X1 - J.anchor[i]);
        }
        if (f >= J.f_s[i]) {  // starts to slip
          J.pinned[i] = 0;
          J.intact[i] = 0;
          if (always) {
            f = law.slipping_force_always(J.A0[i]);
            J.area[i] = law.area(J.A0[i], f);
            J.k[i] = law.stiffness(J.A0[i], J.area[i]);
            J.f_s[i] = law.sigma * J.area[i];
          } else {
            f = law.epsilon * J.f_s[i];
          }
          ++slips;
        }
      } else {
        f = J.force[i];
        if (slow) {  // repins with no force jump
          J.pinned[i] = 1;
          J.anchor[i] = X1 - f / J.k[i];
          any_repin = true;
        }
      }
      J.force[i] = f;
    }
    // Serial sums in index order: the result does not depend on the thread count.
    double F = 0, A = 0;
    std::int64_t ns = 0, ni = 0;
    for (std::size_t i = 0; i < N; ++i) {
      F += J.force[i];
      A += J.area[i];
      ns += !J.pinned[i];
      ni += J.intact[i];
      const double r = J.force[i] / (law.sigma * J.area[i]);
      if (r > max_ratio) max_ratio = r;
    }
    const double gamma1 = (kL * (v * t - X1) - F) / M - m.eta * V;
    const double V1 = V + 0.5 * dt * (gamma + gamma1);
    if (!std::isfinite(X1) || !std::isfinite(V1))
      throw SolverError("reference: non-finite state at t = " + std::to_string(t) + " s");
    info.stats.slips += slips;
    info.stats.repins += any_repin;
    info.stats.force_evals += 1;
    X = X1;
    V = V1;
    gamma = gamma1;
    A_sum = A;
    n_slipping = ns;
    n_intact = ni;
    if (slips > 0 || any_repin)
      rec.population({t, slips, any_repin, ni});
    // Extrema of Q: V crosses v between steps; Q is largest/smallest at the nearer step.
    const double Q = Q_at(n, X);
    if (prevV < v && V >= v) rec.extremum(Q >= prevQ ? Extremum{t, Q, A, true} : Extremum{prevt, prevQ, prevA, true});
    if (prevV > v && V <= v) rec.extremum(Q <= prevQ ? Extremum{t, Q, A, false} : Extremum{prevt, prevQ, prevA, false});
    prevQ = Q; prevA = A; prevV = V; prevt = t;
    emit_samples(n);
  }
  max_ratio_exp = max_ratio / m.epsilon;
  info.max_f_over_sigmaA = max_ratio;
  info.max_f_over_sigma_exp_A = max_ratio_exp;
  info.stats.steps = n - 1;
  info.t_end = static_cast<double>(n - 1) * dt;
  return info;
}

RunInfo integrate(const Scene& scene, Recorder& rec, const RunLimits& limits) {
  return scene.solver.method == SolverMethod::reference ? integrate_reference(scene, rec, limits)
                                                        : integrate_event(scene, rec, limits);
}

}  // namespace asperity
