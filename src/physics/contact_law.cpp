#include "physics/contact_law.hpp"

#include <algorithm>
#include <boost/math/special_functions/ellint_rd.hpp>
#include <boost/math/special_functions/ellint_rf.hpp>
#include <boost/math/tools/roots.hpp>
#include <limits>

namespace asperity {

double stiffness_factor(double r, double nu, JunctionShape shape) {
  if (!(r > 0.0)) return 0.0;  // a vanished junction carries no load
  if (shape == JunctionShape::circular) return std::sqrt(r) / ((1.0 + nu) * (1.0 - 0.5 * nu));
  const double r2 = r * r;  // = 1 − e²
  const double K = boost::math::ellint_rf(0.0, r2, 1.0);
  const double D = boost::math::ellint_rd(0.0, r2, 1.0) / 3.0;  // (K − E)/e²
  return 0.5 * M_PI / ((1.0 + nu) * (K - nu * D));
}

double mindlin_stiffness(double ell_perp, double ell_par, double E, double nu) {
  return ell_perp * E * stiffness_factor(ell_par / ell_perp, nu, JunctionShape::elliptic);
}

double ContactLaw::slip_phi(double A0) const {
  const double beta = sigma * std::sqrt(alpha_b * std::pow(A0, 1.0 - p));
  if (beta < 1e-4) return beta * (1.0 - beta * beta);  // series: avoids cancellation
  return (std::sqrt(1.0 + 4.0 * beta * beta) - 1.0) / (2.0 * beta);
}

double ContactLaw::solve_pinned_force(double A0, double delta) const {
  if (delta == 0.0) return 0.0;
  const double d = std::abs(delta);
  const double k0 = stiffness(A0, A0);
  if (alpha_b == 0.0) return k0 * delta;
  // g(f) = f − k(A(f)) d is increasing; root in (0, min(k0 d, f_max)) since k ≤ k0.
  const double hi = std::min(k0 * d, max_force(A0));
  auto g = [&](double f) { return f - stiffness(A0, area(A0, f)) * d; };
  std::uintmax_t iters = 200;
  auto tol = [](double a, double b) {
    return std::abs(b - a) <= 4 * std::numeric_limits<double>::epsilon() * std::abs(b);
  };
  const auto br = boost::math::tools::bisect(g, 0.0, hi, tol, iters);
  const double f = 0.5 * (br.first + br.second);
  return delta > 0 ? f : -f;
}

double ContactLaw::slipping_force_always(double A0) const {
  // ε σ (A0 − α_b f²/A0^p) = f  →  a f² + f − c = 0, a = εσα_b/A0^p, c = εσA0.
  const double a = epsilon * sigma * alpha_b / std::pow(A0, p);
  const double c = epsilon * sigma * A0;
  if (a * c < 1e-8) return c * (1.0 - a * c);
  return 2.0 * c / (1.0 + std::sqrt(1.0 + 4.0 * a * c));  // stable root form
}

}  // namespace asperity
