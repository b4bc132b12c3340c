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
// expressions the series evaluated per pair before (the same values bit for bit):
//   q_m = (2m−1)!! / (2^m m!) = C(2m, m) / 4^m,  ratio_m = Π_{k≤m} ((2k−1)² − 4) / (2k−1)²,
//   mu_m = the rigid punch's radial moment μ_m (traction_radial_moment), and its recurrence's
//   ratios μ_k/μ_(k−1) = 2k/(2k+1) (rigid_up) and μ_(k−1)/μ_k = (2k+1)/2k, as (2r+3)/(2r+2) at
//   r = k − 1 (rigid_down).
struct SeriesFactors {
  std::array<double, kMaxTerms + 1> q{}, ratio{}, mu_rigid{}, rigid_up{}, rigid_down{};
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
    for (int k = 0; k <= kMaxTerms; ++k) {
      const double r = k;
      rigid_up[k] = (2.0 * k) / (2.0 * k + 1.0);
      rigid_down[k] = (2.0 * r + 3.0) / (2.0 * r + 2.0);
    }
  }
};

// x^m for m = 1, 2, ... (0 ≤ x ≤ 1) as a running product carried in double-double (hi + lo, each
// product's rounding error kept exactly: Dekker's product, or one FMA where the compiler has a
// fast one), so that hi is x^m correctly rounded but within ~m·2^-104 of a tie; std::pow's is
// within 0.52 ulp, so the two agree but in rare cases. A plain running product drifts by
// ~sqrt(m) ulps: that moved C by one ulp on one pair of P3.09N's 430,000, which was enough to
// change a sensitive test's chord iterations (tests/unit/solve/test_solve_interacting_event.cpp,
// "driven far past its slip force"). Veltkamp's split below must not be contracted into FMAs (the
// build is ISO C++, where GCC does not contract).
class RunningPower {
 public:
  explicit RunningPower(double x) : x_(x) {
    const double s = kSplit * x;
    x_hi_ = s - (s - x), x_lo_ = x - x_hi_;
  }
  double next() {  // x^m, m one more than at the last call
    const double p = hi_ * x_;
#ifdef FP_FAST_FMA
    const double e = std::fma(hi_, x_, -p);
#else
    const double s = kSplit * hi_, h1 = s - (s - hi_), h2 = hi_ - h1;
    const double e = ((h1 * x_hi_ - p) + h1 * x_lo_ + h2 * x_hi_) + h2 * x_lo_;
#endif
    const double l = lo_ * x_ + e;
    hi_ = p + l, lo_ = l - (hi_ - p);
    return hi_;
  }

 private:
  static constexpr double kSplit = 134217729.0;  // 2^27 + 1: Veltkamp's split into 26-bit halves
  double x_, x_hi_, x_lo_, hi_ = 1.0, lo_ = 0.0;
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
  // β^2m as a running power (b2 ≤ 1: it only decreases). Once it falls below 2^-900 it is
  // std::pow's, so where β^2m reaches the subnormal range (near-touching discs with β ≲ 0.7,
  // after several hundred terms) the series is summed as it was with std::pow per term.
  // Against the per-term std::pow and the uniform factor's four roundings of before, C moved on
  // 3 of the six stand-ins' 3.3 million pairs (both weightings; ≤ 2.8e-16 relative) and on 6 of
  // the 12.5 million of `bench interacting`'s N = 5,000 population (uniform; ≤ 3.9e-16). It stays
  // symmetric bit for bit: the radii enter only as the smaller and the larger.
  RunningPower b2_power(b2);
  for (int m = 1; m <= kMaxTerms; ++m) {
    const double q = f.q[m];
    const double b2m = b2_power.next();
    const double b2_pow_m = b2m >= 0x1p-900 ? b2m : std::pow(b2, m);
    // ⟨|u|^2m⟩ / d^2m = Σ_p C(m,p)² α^2p β^2(m−p) μ_p μ_(m−p), its terms by recurrence from
    // p = 0 (a zero radius leaves only one term); μ_p/μ_(p−1) = p/(p+1) (uniform) or
    // 2p/(2p+1) (rigid). Uniform: the ratio of successive terms is (α/β)² (m−p+1)(m−p+2) /
    // (p(p+1)), integers exact in double, so rounded once. Rigid: the same factors as before, in
    // the same order (bit for bit).
    double moment = 0.0;
    if (a2 == 0.0 || b2 == 0.0) {
      moment = rigid ? std::pow(a2 + b2, m) * f.mu_rigid[m] : std::pow(a2 + b2, m) / (m + 1.0);
    } else {
      const double x = a2 / b2;
      double t = rigid ? b2_pow_m * f.mu_rigid[m] : b2_pow_m / (m + 1.0);  // p = 0
      moment = t;
      if (rigid) {
        for (int p = 1; p <= m; ++p) {
          const double c = static_cast<double>(m - p + 1) / p;  // C(m,p)/C(m,p−1)
          t *= c * c * x * f.rigid_up[p] * f.rigid_down[m - p];
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
