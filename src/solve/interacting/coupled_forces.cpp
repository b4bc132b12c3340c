#include "solve/interacting/coupled_forces.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "physics/interface_law.hpp"
#include "solve/core/run_info.hpp"
#include "solve/core/run_limits.hpp"

namespace asperity {

struct CoupledForces::Factorisation {
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
};

CoupledForces::CoupledForces(const Problem& problem, const InteractionMatrix& C) : p_(problem), C_(C) {}
CoupledForces::~CoupledForces() = default;

namespace {

// g(f) = f / k(A(f)) of a junction whose area follows its force, within the law's range.
double follow_compliance_times_f(const ContactLaw& law, double A0, double f) {
  return f / contact_at_force(law, A0, f).k;
}

}  // namespace

int CoupledForces::solve(JunctionState& J, const std::vector<std::uint8_t>& solve, double X,
                         std::chrono::steady_clock::time_point deadline) {
  const ContactLaw& law = p_.law;
  const std::size_t N = J.size();
  std::vector<std::size_t> set;
  for (std::size_t i = 0; i < N; ++i)
    if (solve[i]) set.push_back(i);
  const std::size_t n = set.size();
  if (n == 0) return 0;
  // Right-hand side: X − x_i minus the displacement the held junctions cause.
  Eigen::VectorXd rhs(n), f(n);
  std::vector<std::uint8_t> follows(n);
  bool nonlinear = false;
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t i = set[a];
    double r = X - J.anchor[i];
    for (std::size_t j = 0; j < N; ++j)
      if (!solve[j]) r -= C_(i, j) * J.force[j];
    rhs[a] = r;
    f[a] = J.force[i];
    follows[a] = area_follows_force(p_.area_law, J.intact[i]) && law.alpha_b > 0;  // α_b = 0: constant area
    nonlinear = nonlinear || follows[a];
  }
  Eigen::MatrixXd jac(n, n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) jac(a, b) = C_(set[a], set[b]);

  if (!nonlinear) {  // linear: one solve, with the cached factorisation when the set is the same
    if (!cached_ || cached_set_ != set) {
      for (std::size_t a = 0; a < n; ++a) jac(a, a) = 1.0 / J.k[set[a]];
      cached_ = std::make_unique<Factorisation>();
      cached_->ldlt.compute(jac);
      cached_set_ = set;
    }
    f = cached_->ldlt.solve(rhs);
    for (std::size_t a = 0; a < n; ++a) J.force[set[a]] = f[a];
    return 1;
  }
  cached_.reset();
  // Newton: r(f) = g(f) + C f − rhs; the derivative of g of a force-following junction by a
  // central difference (it only sets the convergence rate, not the root).
  double previous = HUGE_VAL;
  for (int iter = 1; iter <= 100; ++iter) {
    if (iter > 1 && std::chrono::steady_clock::now() >= deadline) throw WallTimeReached();
    Eigen::VectorXd g(n);
    for (std::size_t a = 0; a < n; ++a) {
      const std::size_t i = set[a];
      const double A0 = J.A0[i];
      if (follows[a]) {
        const double fmax = law.max_force(A0) * (1 - 1e-9);
        f[a] = std::clamp(f[a], -fmax, fmax);
        g[a] = follow_compliance_times_f(law, A0, f[a]);
        const double h = 1e-6 * std::max(std::abs(f[a]), law.sigma * A0 * 1e-3);
        const double lo = std::max(f[a] - h, -fmax), hi = std::min(f[a] + h, fmax);
        jac(a, a) = (follow_compliance_times_f(law, A0, hi) - follow_compliance_times_f(law, A0, lo)) / (hi - lo);
      } else {
        g[a] = f[a] / J.k[i];
        jac(a, a) = 1.0 / J.k[i];
      }
    }
    Eigen::VectorXd r = g - rhs;
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b)
        if (a != b) r[a] += jac(a, b) * f[b];
    const Eigen::VectorXd step = jac.ldlt().solve(r);
    f -= step;
    double worst = 0;
    for (std::size_t a = 0; a < n; ++a)
      worst = std::max(worst, std::abs(step[a]) / (std::abs(f[a]) + law.sigma * J.A0[set[a]] * 1e-9));
    // Converged at 1e-14, or stalled at rounding (an ill-conditioned dense system: the step
    // stops shrinking once it is of the order of the residual's rounding).
    const bool stalled = iter >= 3 && worst < 1e-10 && worst > 0.5 * previous;
    previous = worst;
    if (worst <= 1e-14 || stalled) {
      for (std::size_t a = 0; a < n; ++a) {
        const std::size_t i = set[a];
        J.force[i] = f[a];
        if (follows[a]) J.set_contact(i, contact_at_force(law, J.A0[i], f[a]));
      }
      return iter;
    }
  }
  throw SolverError("interacting junctions: Newton did not converge in 100 iterations at X = " + std::to_string(X) +
                    " m");
}

}  // namespace asperity
