#include "surface/normal_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>

#include "surface/fft_planner.hpp"

namespace asperity {
namespace {

// Convolution of an n × n field with a fixed kernel by FFT on an N × N grid: N = 2n with zero
// padding (linear, an isolated contact) or N = n (periodic).
class Convolution {
 public:
  // A kernel given in real space on N × N (wrapped offsets).
  Convolution(std::size_t n, std::size_t N, const std::vector<double>& kernel)
      : n_(n), N_(N), nc_(N_ / 2 + 1), fft_(N_), kernel_(N_ * nc_) {
    std::copy(kernel.begin(), kernel.end(), fft_.real());
    fft_.forward();
    for (std::size_t k = 0; k < N_ * nc_; ++k) kernel_[k] = {fft_.spectrum()[k][0], fft_.spectrum()[k][1]};
  }
  // A kernel given by its spectrum: value at the wavevector indices (ky, kx), kx ≥ 0.
  template <class F>
  Convolution(std::size_t n, F spectrum) : n_(n), N_(n), nc_(n / 2 + 1), fft_(n), kernel_(N_ * nc_) {
    for (std::size_t i = 0; i < N_; ++i)
      for (std::size_t j = 0; j < nc_; ++j) {
        const long ky = i <= N_ / 2 ? static_cast<long>(i) : static_cast<long>(i) - static_cast<long>(N_);
        kernel_[i * nc_ + j] = {spectrum(ky, static_cast<long>(j)), 0.0};
      }
  }

  // out = kernel ∗ in (both n × n).
  void apply(const std::vector<double>& in, std::vector<double>& out) {
    double* real = fft_.real();
    std::fill(real, real + N_ * N_, 0.0);
    for (std::size_t i = 0; i < n_; ++i) std::copy(&in[i * n_], &in[i * n_] + n_, real + i * N_);
    fft_.forward();
    const double scale = 1.0 / static_cast<double>(N_ * N_);
    fftw_complex* spec = fft_.spectrum();
    for (std::size_t k = 0; k < N_ * nc_; ++k) {
      const double a = spec[k][0], b = spec[k][1], c = kernel_[k].first, d = kernel_[k].second;
      spec[k][0] = (a * c - b * d) * scale;
      spec[k][1] = (a * d + b * c) * scale;
    }
    fft_.inverse();
    for (std::size_t i = 0; i < n_; ++i) std::copy(real + i * N_, real + i * N_ + n_, &out[i * n_]);
  }

 private:
  std::size_t n_, N_, nc_;
  FftBuffers fft_;
  std::vector<std::pair<double, double>> kernel_;  // its spectrum
};

}  // namespace

double love_rectangle(double x, double y, double a, double b) {
  // a, b: half-sides. Johnson (1985) eq. 3.25 with E* = E/(1 − ν²): u = F / (π E*).
  auto term = [](double s, double t1, double t2) {  // s · ln((t1 + √(t1² + s²)) / (t2 + √(t2² + s²)))
    if (s == 0) return 0.0;
    return s * std::log((t1 + std::hypot(t1, s)) / (t2 + std::hypot(t2, s)));
  };
  const double F = term(x + a, y + b, y - b) + term(y + b, x + a, x - a) + term(x - a, y - b, y + b) +
                   term(y - b, x - a, x + a);
  return F / std::numbers::pi;
}

NormalContact solve_normal_contact(const HeightMap& map, const NormalContactSettings& s) {
  const std::size_t n = map.n;
  if (n < 2 || map.h_m.size() != n * n || !(map.pixel_m > 0) || !std::isfinite(map.pixel_m))
    throw std::invalid_argument("normal contact: an n x n height map with n >= 2 and a positive pixel size is needed");
  if (!(s.E_star_Pa > 0) || !std::isfinite(s.E_star_Pa) || !(s.load_N > 0) || !std::isfinite(s.load_N))
    throw std::invalid_argument("normal contact: E* and the load must be positive and finite");
  for (const double h : map.h_m)
    if (!std::isfinite(h)) throw std::invalid_argument("normal contact: a height is not finite");
  const double A = map.pixel_m * map.pixel_m, half = 0.5 * map.pixel_m;
  const std::size_t N = 2 * n;

  std::optional<Convolution> convolution;
  if (s.periodic) {
    // u(q) = 2 p(q) / (E* |q|); the mean (q = 0) displacement is the free approach.
    const double qL = 2 * std::numbers::pi / map.length_m();
    convolution.emplace(n, [&](long ky, long kx) {
      const double q = qL * std::hypot(static_cast<double>(ky), static_cast<double>(kx));
      return q > 0 ? 2.0 / (s.E_star_Pa * q) : 0.0;
    });
  } else {
    // Influence of a unit pressure on one pixel, at every offset (wrapped on the 2n grid).
    std::vector<double> kernel(N * N, 0.0);
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = 0; j < N; ++j) {
        const double di = static_cast<double>(i) - (i < n ? 0.0 : static_cast<double>(N));  // offsets −n..n−1
        const double dj = static_cast<double>(j) - (j < n ? 0.0 : static_cast<double>(N));
        kernel[i * N + j] = love_rectangle(dj * map.pixel_m, di * map.pixel_m, half, half) / s.E_star_Pa;
      }
    convolution.emplace(n, N, kernel);
  }
  Convolution& K = *convolution;

  // Separation from the flat touching the highest summit.
  const double top = *std::max_element(map.h_m.begin(), map.h_m.end());
  std::vector<double> h0(n * n);
  for (std::size_t k = 0; k < n * n; ++k) h0[k] = top - map.h_m[k];

  NormalContact out;
  std::vector<double>& p = out.pressure_Pa;
  p.assign(n * n, s.load_N / (A * static_cast<double>(n * n)));
  std::vector<double> u(n * n), g(n * n), t(n * n, 0.0), r(n * n), p_old(n * n);
  double G_old = 1.0;
  bool delta = false;
  double gbar = 0;
  for (int it = 1; it <= s.max_iterations; ++it) {
    K.apply(p, u);
    // Gap on the contact set, shifted by its mean there (the unknown approach).
    double sum = 0;
    std::size_t nc = 0;
    for (std::size_t k = 0; k < n * n; ++k) {
      g[k] = u[k] + h0[k];
      if (p[k] > 0) sum += g[k], ++nc;
    }
    gbar = nc ? sum / static_cast<double>(nc) : 0.0;
    double G = 0;
    for (std::size_t k = 0; k < n * n; ++k) {
      g[k] -= gbar;
      if (p[k] > 0) G += g[k] * g[k];
    }
    // Conjugate direction on the contact set.
    const double beta = delta ? G / G_old : 0.0;
    for (std::size_t k = 0; k < n * n; ++k) t[k] = p[k] > 0 ? g[k] + beta * t[k] : 0.0;
    G_old = G;
    K.apply(t, r);
    double rsum = 0;
    for (std::size_t k = 0; k < n * n; ++k)
      if (p[k] > 0) rsum += r[k];
    const double rbar = nc ? rsum / static_cast<double>(nc) : 0.0;
    double gt = 0, rt = 0;
    for (std::size_t k = 0; k < n * n; ++k)
      if (p[k] > 0) gt += g[k] * t[k], rt += (r[k] - rbar) * t[k];
    const double tau = rt != 0 ? gt / rt : 0.0;
    p_old = p;
    for (std::size_t k = 0; k < n * n; ++k) {
      if (p[k] > 0) p[k] = std::max(0.0, p[k] - tau * t[k]);
    }
    // Points outside the contact that the flat overlaps join it.
    delta = true;
    for (std::size_t k = 0; k < n * n; ++k)
      if (p_old[k] <= 0 && g[k] < 0) {
        p[k] = -tau * g[k];
        delta = false;
      }
    // The load.
    double total = 0;
    for (const double x : p) total += x;
    total *= A;
    if (!(total > 0)) throw std::runtime_error("normal contact: the pressures vanished (CG breakdown)");
    const double f = s.load_N / total;
    double change = 0;
    for (std::size_t k = 0; k < n * n; ++k) {
      p[k] *= f;
      change += std::abs(p[k] - p_old[k]);
    }
    out.iterations = it;
    out.residual = change * A / s.load_N;
    if (out.residual < s.tolerance) {
      out.converged = true;
      break;
    }
  }
  K.apply(p, u);
  double area = 0, sum = 0;
  std::size_t nc = 0;
  for (std::size_t k = 0; k < n * n; ++k)
    if (p[k] > 0) area += A, sum += u[k] + h0[k], ++nc;
  out.area_m2 = area;
  const double shift = nc ? sum / static_cast<double>(nc) : 0.0;  // u + h0 on the contact = approach
  out.approach_m = shift;
  out.gap_m.resize(n * n);
  for (std::size_t k = 0; k < n * n; ++k) out.gap_m[k] = std::max(0.0, u[k] + h0[k] - shift);
  return out;
}

}  // namespace asperity
