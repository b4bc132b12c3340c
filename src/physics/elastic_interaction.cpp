#include "physics/elastic_interaction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace asperity {

namespace {
double prefactor(double E_pa, double nu) { return (1.0 + nu) / (2.0 * M_PI * E_pa); }
}  // namespace

double traction_radial_moment(int m, TractionWeighting weighting) {
  // By the ratios μ_k/μ_(k−1) = k/(k+1) (uniform) or 2k/(2k+1) (rigid), as disc_compliance's
  // recurrence uses them.
  double mu = 1.0;
  for (int k = 1; k <= m; ++k)
    mu *= weighting == TractionWeighting::rigid ? 2.0 * k / (2.0 * k + 1.0) : static_cast<double>(k) / (k + 1.0);
  return mu;
}

double cerruti_compliance(double dx_m, double dy_m, double E_pa, double nu) {
  const double r = std::hypot(dx_m, dy_m);
  return prefactor(E_pa, nu) * (2.0 * (1.0 - nu) / r + 2.0 * nu * dx_m * dx_m / (r * r * r));
}

double disc_compliance(double dx_m, double dy_m, double a_i_m, double a_j_m, double E_pa, double nu,
                       TractionWeighting weighting) {
  const double d = std::hypot(dx_m, dy_m);
  if (!(d >= a_i_m + a_j_m) || !(a_i_m >= 0) || !(a_j_m >= 0))
    throw std::invalid_argument("disc_compliance: discs overlap or radii are invalid");
  const bool rigid = weighting == TractionWeighting::rigid;
  const double cos2 = (dx_m * dx_m - dy_m * dy_m) / (d * d);
  // In units of d: α = a_i/d, β = a_j/d with α + β ≤ 1.
  // The moments are symmetric in the two radii; their recurrence starts from β^2m, so β is the
  // larger: from the smaller one, β^2m underflowed for near-touching unequal discs after a few
  // hundred terms and C_ij and C_ji differed (by up to 4e-6 on the stand-ins' closest pairs).
  const double small = std::min(a_i_m, a_j_m), large = std::max(a_i_m, a_j_m);
  const double a2 = (small / d) * (small / d), b2 = (large / d) * (large / d);
  double g = 1.0, h = 1.0;   // Σ of the 1/r and cos2θ/r series, times d
  double q = 1.0;            // (2m−1)!! / (2^m m!) = C(2m, m) / 4^m
  double ratio = 1.0;        // Π_{k≤m} ((2k−1)² − 4) / (2k−1)²
  double mu_m = 1.0;         // rigid: the radial moment μ_m = ⟨|ξ|^2m⟩ / a^2m of the punch's traction
  constexpr int kMaxTerms = 2000;
  for (int m = 1; m <= kMaxTerms; ++m) {
    q *= (2.0 * m - 1.0) / (2.0 * m);
    const double odd = 2.0 * m - 1.0;
    ratio *= (odd * odd - 4.0) / (odd * odd);
    if (rigid) mu_m *= (2.0 * m) / (2.0 * m + 1.0);
    // ⟨|u|^2m⟩ / d^2m = Σ_p C(m,p)² α^2p β^2(m−p) μ_p μ_(m−p), its terms by recurrence from
    // p = 0 (a zero radius leaves only one term); μ_p/μ_(p−1) = p/(p+1) (uniform) or
    // 2p/(2p+1) (rigid).
    // (The uniform case keeps its original expressions, bit for bit.)
    double moment = 0.0;
    if (a2 == 0.0 || b2 == 0.0) {
      moment = rigid ? std::pow(a2 + b2, m) * mu_m : std::pow(a2 + b2, m) / (m + 1.0);
    } else {
      double t = rigid ? std::pow(b2, m) * mu_m : std::pow(b2, m) / (m + 1.0);  // p = 0
      moment = t;
      for (int p = 1; p <= m; ++p) {
        const double c = static_cast<double>(m - p + 1) / p;  // C(m,p)/C(m,p−1)
        if (rigid) {
          const double r = m - p;
          t *= c * c * (a2 / b2) * ((2.0 * p) / (2.0 * p + 1.0)) * ((2.0 * r + 3.0) / (2.0 * r + 2.0));
        } else {
          t *= c * c * (a2 / b2) * (static_cast<double>(p) * (m - p + 2)) / ((p + 1.0) * (m - p + 1.0));
        }
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

double rigid_punch_displacement(double x_m, double y_m, double a_m, double E_pa, double nu, int n_angles) {
  const double r2 = x_m * x_m + y_m * y_m;
  if (!(a_m > 0) || !(r2 < a_m * a_m) || n_angles < 4)
    throw std::invalid_argument("rigid_punch_displacement: the point must lie inside the disc");
  // Along the ray from P in direction e(θ): K = c[2(1−ν) + 2ν cos²θ]/ρ, dA = ρ dρ dθ, and the
  // traction 1/(2πa sqrt(a² − |P + ρe|²)) = 1/(2πa sqrt((L − ρ)(ρ + L₂))), L and L₂ the
  // distances to the edge ahead and behind; ∫₀^L dρ / sqrt((L − ρ)(ρ + L₂)) = π/2 +
  // asin((L − L₂)/(L + L₂)).
  double sum = 0;
  for (int k = 0; k < n_angles; ++k) {
    const double th = 2.0 * M_PI * k / n_angles;
    const double ex = std::cos(th), ey = std::sin(th);
    const double b = x_m * ex + y_m * ey;
    const double disc = std::sqrt(b * b + a_m * a_m - r2);
    const double L = disc - b, L2 = disc + b;
    const double radial = 0.5 * M_PI + std::asin((L - L2) / (L + L2));
    sum += (2.0 * (1.0 - nu) + 2.0 * nu * ex * ex) * radial;
  }
  return prefactor(E_pa, nu) * sum * (2.0 * M_PI / n_angles) / (2.0 * M_PI * a_m);
}

}  // namespace asperity
