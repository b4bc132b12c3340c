#include "physics/elastic_interaction.hpp"

#include <cmath>
#include <stdexcept>

namespace asperity {

namespace {
double prefactor(double E_pa, double nu) { return (1.0 + nu) / (2.0 * M_PI * E_pa); }
}  // namespace

double cerruti_compliance(double dx_m, double dy_m, double E_pa, double nu) {
  const double r = std::hypot(dx_m, dy_m);
  return prefactor(E_pa, nu) * (2.0 * (1.0 - nu) / r + 2.0 * nu * dx_m * dx_m / (r * r * r));
}

double disc_compliance(double dx_m, double dy_m, double a_i_m, double a_j_m, double E_pa, double nu) {
  const double d = std::hypot(dx_m, dy_m);
  if (!(d >= a_i_m + a_j_m) || !(a_i_m >= 0) || !(a_j_m >= 0))
    throw std::invalid_argument("disc_compliance: discs overlap or radii are invalid");
  const double cos2 = (dx_m * dx_m - dy_m * dy_m) / (d * d);
  // In units of d: α = a_i/d, β = a_j/d with α + β ≤ 1.
  const double a2 = (a_i_m / d) * (a_i_m / d), b2 = (a_j_m / d) * (a_j_m / d);
  double g = 1.0, h = 1.0;   // Σ of the 1/r and cos2θ/r series, times d
  double q = 1.0;            // (2m−1)!! / (2^m m!) = C(2m, m) / 4^m
  double ratio = 1.0;        // Π_{k≤m} ((2k−1)² − 4) / (2k−1)²
  constexpr int kMaxTerms = 2000;
  for (int m = 1; m <= kMaxTerms; ++m) {
    q *= (2.0 * m - 1.0) / (2.0 * m);
    const double odd = 2.0 * m - 1.0;
    ratio *= (odd * odd - 4.0) / (odd * odd);
    // ⟨|u|^2m⟩ / d^2m = Σ_p C(m,p)² α^2p β^2(m−p) / ((p+1)(m−p+1)), its terms by recurrence
    // from p = 0 (a zero radius leaves only one term).
    double moment = 0.0;
    if (a2 == 0.0 || b2 == 0.0) {
      moment = std::pow(a2 + b2, m) / (m + 1.0);
    } else {
      double t = std::pow(b2, m) / (m + 1.0);  // p = 0
      moment = t;
      for (int p = 1; p <= m; ++p) {
        const double c = static_cast<double>(m - p + 1) / p;  // C(m,p)/C(m,p−1)
        t *= c * c * (a2 / b2) * (static_cast<double>(p) * (m - p + 2)) / ((p + 1.0) * (m - p + 1.0));
        moment += t;
      }
    }
    const double term = moment * q * q;
    g += term;
    h += term * ratio;
    if (term < 1e-17 * g) break;
  }
  return prefactor(E_pa, nu) * ((2.0 - nu) * g + nu * cos2 * h) / d;
}

}  // namespace asperity
