#include "physics/elastic_interaction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace asperity {

namespace {
double prefactor(double E_pa, double nu) { return (1.0 + nu) / (2.0 * M_PI * E_pa); }

constexpr int kMaxTerms = 2000;  // disc_compliance's series: at most this many terms

// disc_compliance's pair-independent factors by term m (1..kMaxTerms), tabulated once by the
// recurrences the series ran per pair before (the same values bit for bit):
//   q_m = (2m−1)!! / (2^m m!) = C(2m, m) / 4^m,  ratio_m = Π_{k≤m} ((2k−1)² − 4) / (2k−1)²,
//   mu_m = the rigid punch's radial moment μ_m (traction_radial_moment).
struct SeriesFactors {
  std::array<double, kMaxTerms + 1> q{}, ratio{}, mu_rigid{};
  SeriesFactors() {
    double qm = 1.0, ratio_m = 1.0, mu_m = 1.0;
    q[0] = ratio[0] = mu_rigid[0] = 1.0;
    for (int m = 1; m <= kMaxTerms; ++m) {
      qm *= (2.0 * m - 1.0) / (2.0 * m);
      const double odd = 2.0 * m - 1.0;
      ratio_m *= (odd * odd - 4.0) / (odd * odd);
      mu_m *= (2.0 * m) / (2.0 * m + 1.0);
      q[m] = qm, ratio[m] = ratio_m, mu_rigid[m] = mu_m;
    }
  }
};
const SeriesFactors& series_factors() {
  static const SeriesFactors factors;  // built on first use (thread-safe)
  return factors;
}
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
  return disc_compliance_at_distance(dx_m, dy_m, std::hypot(dx_m, dy_m), a_i_m, a_j_m, E_pa, nu, weighting);
}

double disc_compliance_at_distance(double dx_m, double dy_m, double d, double a_i_m, double a_j_m, double E_pa,
                                   double nu, TractionWeighting weighting) {
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
  const SeriesFactors& f = series_factors();
  double g = 1.0, h = 1.0;  // Σ of the 1/r and cos2θ/r series, times d
  // β^2m as a running power (b2 ≤ 1: it only decreases; it drifts from std::pow's by a few ulps
  // over many terms). Once it falls below 2^-900 it is std::pow's again, so where β^2m reaches
  // the subnormal range (near-touching discs with β ≲ 0.7, after several hundred terms) the
  // series is summed as it was with std::pow per term. With the single-rounding factors below,
  // C moved by ≤ 5.1e-16 relative from the per-term std::pow and four-rounding factors of
  // before (all pairs of the 5,000-junction stand-in population, both weightings), and stays
  // symmetric bit for bit (everything depends on the radii only through the smaller and larger).
  double b2m = 1.0;
  for (int m = 1; m <= kMaxTerms; ++m) {
    const double q = f.q[m];
    b2m *= b2;
    const double b2_pow_m = b2m >= 0x1p-900 ? b2m : std::pow(b2, m);
    // ⟨|u|^2m⟩ / d^2m = Σ_p C(m,p)² α^2p β^2(m−p) μ_p μ_(m−p), its terms by recurrence from
    // p = 0 (a zero radius leaves only one term). With μ_p/μ_(p−1) = p/(p+1) (uniform) or
    // 2p/(2p+1) (rigid), the ratio of successive terms is (α/β)² times
    //   uniform: (m−p+1)(m−p+2) / (p(p+1)),  rigid: (m−p+1)(2m−2p+3) / (p(2p+1)),
    // integers exact in double, so each factor is rounded once.
    double moment = 0.0;
    if (a2 == 0.0 || b2 == 0.0) {
      moment = rigid ? std::pow(a2 + b2, m) * f.mu_rigid[m] : std::pow(a2 + b2, m) / (m + 1.0);
    } else {
      const double x = a2 / b2;
      double t = rigid ? b2_pow_m * f.mu_rigid[m] : b2_pow_m / (m + 1.0);  // p = 0
      moment = t;
      if (rigid) {
        for (int p = 1; p <= m; ++p) {
          t *= x * ((static_cast<double>(m - p + 1) * (2 * (m - p) + 3)) / (static_cast<double>(p) * (2 * p + 1)));
          moment += t;
        }
      } else {
        for (int p = 1; p <= m; ++p) {
          t *= x * ((static_cast<double>(m - p + 1) * (m - p + 2)) / (static_cast<double>(p) * (p + 1)));
          moment += t;
        }
      }
    }
    const double term = moment * q * q;
    g += term;
    h += term * f.ratio[m];
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
