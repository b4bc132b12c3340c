#include "surface/tangential_contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "surface/bounded_cg.hpp"
#include "surface/fft_convolution.hpp"
#include "surface/pixel_loops.hpp"

namespace asperity {
using pixel_loops::Workers;

namespace {

// Y asinh(X / |Y|), 0 on Y = 0 (its limit).
double y_asinh(double X, double Y) { return Y == 0 ? 0.0 : Y * std::asinh(X / std::abs(Y)); }

// Σ over the corners of [X1, X2] × [Y1, Y2] with signs + − − +: the double integral of a function
// whose mixed second derivative is F's.
template <class F>
double corners(double x, double y, double a, double b, F f) {
  return f(x + a, y + b) - f(x - a, y + b) - f(x + a, y - b) + f(x - a, y - b);
}

std::vector<double> bound_where_pressed(const NormalContact& c, auto value) {
  std::vector<double> b(c.pressure_Pa.size(), 0.0);
  for (std::size_t k = 0; k < b.size(); ++k)
    if (c.pressure_Pa[k] > 0) b[k] = value(c.pressure_Pa[k]);
  return b;
}

}  // namespace

std::vector<double> shear_strength_bound(const NormalContact& contact, double shear_strength_Pa) {
  if (!(shear_strength_Pa > 0) || !std::isfinite(shear_strength_Pa))
    throw std::invalid_argument("tangential contact: the shear strength must be positive and finite");
  return bound_where_pressed(contact, [&](double) { return shear_strength_Pa; });
}

std::vector<double> coulomb_bound(const NormalContact& contact, double friction_coefficient) {
  if (!(friction_coefficient > 0) || !std::isfinite(friction_coefficient))
    throw std::invalid_argument("tangential contact: the friction coefficient must be positive and finite");
  return bound_where_pressed(contact, [&](double p) { return friction_coefficient * p; });
}

double cerruti_pixel_compliance(double x, double y, double a, double b, double E_Pa, double nu) {
  // ∫∫ 1/r = Σ± [X asinh(Y/|X|) + Y asinh(X/|Y|)] (Love's rectangle); ∫∫ X²/r³ = Σ± Y asinh(X/|Y|)
  // (integrate in Y: Y/r; then in X), X, Y the offsets from a point of the pixel.
  const double inv_r = corners(x, y, a, b, [](double X, double Y) { return y_asinh(Y, X) + y_asinh(X, Y); });
  const double x2_r3 = corners(x, y, a, b, [](double X, double Y) { return y_asinh(X, Y); });
  return (1 + nu) / (std::numbers::pi * E_Pa) * ((1 - nu) * inv_r + nu * x2_r3);
}

// The elastic operator u_x = K q on the padded grid, and the threads it runs on.
struct TangentialContact::Operator {
  Workers workers;
  PaddedConvolution K;
  Operator(std::size_t n, std::vector<double> influence, int threads)
      : workers(threads), K(n, std::move(influence), workers) {}
};

TangentialContact::TangentialContact(std::size_t n, double pixel_m, std::vector<double> bound_Pa,
                                     const TangentialContactSettings& s)
    : n_(n), pixel_m_(pixel_m), bound_(std::move(bound_Pa)), settings_(s) {
  if (n < 2 || bound_.size() != n * n || !(pixel_m > 0) || !std::isfinite(pixel_m))
    throw std::invalid_argument(
        "tangential contact: n x n traction bounds with n >= 2 and a positive pixel size are needed");
  if (s.nu != 0.5)
    throw std::invalid_argument(
        "tangential contact: only nu = 0.5 is solved (at other nu shear changes the normal pressures, a coupling this "
        "solver leaves out)");
  if (!(s.E_Pa > 0) || !std::isfinite(s.E_Pa))
    throw std::invalid_argument("tangential contact: E must be positive and finite");
  if (!(s.tolerance > 0) || s.max_iterations < 1)
    throw std::invalid_argument("tangential contact: the tolerance and the iteration limit must be positive");
  for (const double b : bound_)
    if (!(b >= 0) || !std::isfinite(b))
      throw std::invalid_argument("tangential contact: a traction bound is negative or not finite");
  // The kernel at offsets (|di|, |dj|): even in both, as Cerruti's x-x kernel is.
  std::vector<double> influence((n + 1) * (n + 1));
  const double h = 0.5 * pixel_m;
  for (std::size_t i = 0; i <= n; ++i)
    for (std::size_t j = 0; j <= n; ++j)
      influence[i * (n + 1) + j] = cerruti_pixel_compliance(static_cast<double>(j) * pixel_m,
                                                            static_cast<double>(i) * pixel_m, h, h, s.E_Pa, s.nu);
  op_ = std::make_unique<Operator>(n, std::move(influence), s.threads);
  q_.assign(n * n, 0.0);
}

TangentialContact::~TangentialContact() = default;

void TangentialContact::iterate(double delta, const std::vector<unsigned char>& free, bool bounded,
                                std::vector<double>& q, TangentialState& st) {
  BoundedCgSettings cs;
  cs.tolerance = settings_.tolerance;
  cs.max_iterations = settings_.max_iterations;
  PaddedConvolution& K = op_->K;
  const BoundedCgResult r =
      bounded_cg([&](const std::vector<double>& in, std::vector<double>& out) { K.apply(in, out); }, delta, free,
                 bounded ? &bound_ : nullptr, q, cs, op_->workers);
  st.iterations = r.iterations;
  st.convolutions = r.products;
  st.residual = r.residual;
  st.converged = r.converged;
}

TangentialState TangentialContact::solve(double delta) {
  if (!(delta >= 0) || !std::isfinite(delta))
    throw std::invalid_argument("tangential contact: the displacement must be non-negative and finite");
  const std::size_t nn = n_ * n_;
  TangentialState st;
  st.displacement_m = delta;
  std::vector<unsigned char> contact(nn);
  for (std::size_t k = 0; k < nn; ++k) contact[k] = bound_[k] > 0, st.contact_pixels += contact[k];
  // Start: the last state scaled to δ, clipped (exact while no pixel starts or stops slipping).
  const double scale = last_delta_ > 0 ? delta / last_delta_ : 0.0;
  for (std::size_t k = 0; k < nn; ++k) q_[k] = std::clamp(q_[k] * scale, -bound_[k], bound_[k]);
  last_delta_ = delta;
  if (delta == 0) {
    st.converged = true;
    return st;
  }
  iterate(delta, contact, true, q_, st);
  double sum = 0;
  for (std::size_t k = 0; k < nn; ++k) {
    sum += q_[k];
    st.slipping_pixels += contact[k] && std::abs(q_[k]) >= bound_[k];
  }
  st.force_N = sum * pixel_m_ * pixel_m_;
  return st;
}

// dq solves K dq = 1 on the sticking pixels, dq = 0 elsewhere (slipping pixels held at their
// bounds): the stiffness Σ dq A of those pixels moving together.
double TangentialContact::sticking_stiffness(const std::vector<unsigned char>& sticking) {
  if (std::find(sticking.begin(), sticking.end(), 1) == sticking.end()) return 0.0;
  std::vector<double> dq(n_ * n_, 0.0);
  TangentialState st;
  iterate(1.0, sticking, false, dq, st);
  if (!st.converged) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0;
  for (const double x : dq) sum += x;
  return sum * pixel_m_ * pixel_m_;
}

double TangentialContact::tangent_stiffness_N_per_m() {
  std::vector<unsigned char> stick(n_ * n_);
  for (std::size_t k = 0; k < stick.size(); ++k) stick[k] = bound_[k] > 0 && std::abs(q_[k]) < bound_[k];
  return sticking_stiffness(stick);
}

double TangentialContact::initial_stiffness_N_per_m() {
  std::vector<unsigned char> contact(n_ * n_);
  for (std::size_t k = 0; k < contact.size(); ++k) contact[k] = bound_[k] > 0;
  return sticking_stiffness(contact);
}

double TangentialContact::full_sliding_force_N() const {
  double sum = 0;
  for (const double b : bound_) sum += b;
  return sum * pixel_m_ * pixel_m_;
}

double TangentialContact::full_sliding_displacement_m() {
  std::vector<double> u(n_ * n_);
  op_->K.apply(bound_, u);
  double top = 0;
  for (std::size_t k = 0; k < u.size(); ++k)
    if (bound_[k] > 0) top = std::max(top, u[k]);
  return top;
}

std::vector<unsigned char> TangentialContact::slip_map() const {
  std::vector<unsigned char> m(n_ * n_, 0);
  for (std::size_t k = 0; k < m.size(); ++k)
    if (bound_[k] > 0) m[k] = std::abs(q_[k]) >= bound_[k] ? 2 : 1;
  return m;
}

TangentialCurve tangential_curve(TangentialContact& contact, const std::vector<double>& displacements_m,
                                 bool tangent_stiffness, bool keep_slip_maps) {
  TangentialCurve c;
  c.initial_stiffness_N_per_m = contact.initial_stiffness_N_per_m();
  c.full_sliding_force_N = contact.full_sliding_force_N();
  c.full_sliding_displacement_m = contact.full_sliding_displacement_m();
  contact.solve(0.0);
  std::vector<unsigned char> before = contact.slip_map();
  double last = 0;
  for (const double delta : displacements_m) {
    if (!(delta >= last)) throw std::invalid_argument("tangential curve: the displacements must increase from 0");
    last = delta;
    const TangentialState st = contact.solve(delta);
    std::vector<unsigned char> now = contact.slip_map();
    for (std::size_t k = 0; k < now.size(); ++k)
      if (before[k] == 2 && now[k] != 2) c.monotone = false;
    if (keep_slip_maps) c.slip_maps.push_back(now);
    before.swap(now);
    TangentialCurvePoint p;
    p.displacement_m = delta;
    p.force_N = st.force_N;
    p.tangent_stiffness_N_per_m =
        tangent_stiffness ? contact.tangent_stiffness_N_per_m() : std::numeric_limits<double>::quiet_NaN();
    p.slip_area_fraction =
        st.contact_pixels ? static_cast<double>(st.slipping_pixels) / static_cast<double>(st.contact_pixels) : 0.0;
    p.iterations = st.iterations;
    p.converged = st.converged;
    c.points.push_back(p);
  }
  return c;
}

}  // namespace asperity
