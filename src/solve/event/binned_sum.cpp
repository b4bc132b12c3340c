#include "solve/event/binned_sum.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace asperity {

BinnedUniversalSum::BinnedUniversalSum(const UniversalForceLaw& law, const std::vector<double>& w,
                                       const std::vector<double>& c, const std::vector<double>& A0, double rel_width)
    : law_(law) {
  const std::size_t N = w.size();
  if (c.size() != N || A0.size() != N) throw std::invalid_argument("BinnedUniversalSum: sizes differ");
  if (!(rel_width > 0)) throw std::invalid_argument("BinnedUniversalSum: rel_width must be > 0");
  std::vector<std::int64_t> key(N);
  for (std::size_t i = 0; i < N; ++i) {
    if (!(c[i] > 0)) throw std::invalid_argument("BinnedUniversalSum: c must be > 0");
    key[i] = static_cast<std::int64_t>(std::floor(std::log(c[i]) / rel_width));
  }
  std::vector<std::uint32_t> order(N);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return key[a] != key[b] ? key[a] < key[b] : a < b; });
  w_.resize(N);
  c_.resize(N);
  A0_.resize(N);
  slot_of_.resize(N);
  bin_of_.resize(N);
  present_flag_.assign(N, 1);
  for (std::size_t s = 0; s < N; ++s) {
    const std::uint32_t i = order[s];
    if (s == 0 || key[i] != key[order[s - 1]]) {
      Bin b;
      b.c_mid = std::exp((static_cast<double>(key[i]) + 0.5) * rel_width);
      b.begin = static_cast<std::uint32_t>(s);
      bins_.push_back(b);
    }
    Bin& b = bins_.back();
    b.end = static_cast<std::uint32_t>(s + 1);
    ++b.count;
    w_[s] = w[i];
    c_[s] = c[i];
    A0_[s] = A0[i];
    slot_of_[i] = static_cast<std::uint32_t>(s);
    bin_of_[s] = static_cast<std::uint32_t>(bins_.size() - 1);
    const double u = c[i] - b.c_mid;
    double un = 1.0;
    for (int n = 0; n < 4; ++n, un *= u) {
      b.mw[n] += w[i] * un;
      b.ma[n] += A0[i] * un;
    }
  }
  present_ = N;
}

void BinnedUniversalSum::remove(std::size_t i) {
  const std::uint32_t s = slot_of_[i];
  if (!present_flag_[s]) return;
  present_flag_[s] = 0;
  --present_;
  Bin& b = bins_[bin_of_[s]];
  if (--b.count == 0) {  // exactly empty, whatever the rounding of the subtractions
    std::fill(std::begin(b.mw), std::end(b.mw), 0.0);
    std::fill(std::begin(b.ma), std::end(b.ma), 0.0);
    return;
  }
  const double u = c_[s] - b.c_mid;
  double un = 1.0;
  for (int n = 0; n < 4; ++n, un *= u) {
    b.mw[n] -= w_[s] * un;
    b.ma[n] -= A0_[s] * un;
  }
}

double BinnedUniversalSum::exact_force(const Bin& b, double X) const {
  double F = 0;
  for (std::uint32_t s = b.begin; s < b.end; ++s)
    if (present_flag_[s]) F += w_[s] * law_.g(c_[s] * X);
  return F * X;
}

double BinnedUniversalSum::exact_area(const Bin& b, double X) const {
  double A = 0;
  for (std::uint32_t s = b.begin; s < b.end; ++s) {
    if (!present_flag_[s]) continue;
    const double psi = c_[s] * X, phi = psi * law_.g(psi);
    A += sheared_area_phi(A0_[s], phi);
  }
  return A;
}

double BinnedUniversalSum::force(double X) const {
  double S = 0;
  for (const Bin& b : bins_) {
    if (b.count == 0) continue;
    double d[4];
    if (!law_.g_derivatives(b.c_mid * X, d)) {
      S += exact_force(b, X);
      continue;
    }
    // X · Σ_n g⁽ⁿ⁾(ψ̄) Xⁿ/n! M_n, Horner in X.
    S += X * (b.mw[0] * d[0] + X * (b.mw[1] * d[1] + X * (b.mw[2] * d[2] / 2 + X * b.mw[3] * d[3] / 6)));
  }
  return S;
}

double BinnedUniversalSum::area(double X) const {
  double A = 0;
  for (const Bin& b : bins_) {
    if (b.count == 0) continue;
    const double psi = b.c_mid * X;
    double d[4];
    if (!law_.g_derivatives(psi, d)) {
      A += exact_area(b, X);
      continue;
    }
    // h(ψ) = φ² = P², P = ψ g: derivatives of P, then of P².
    const double P = psi * d[0], P1 = d[0] + psi * d[1], P2 = 2 * d[1] + psi * d[2], P3 = 3 * d[2] + psi * d[3];
    const double h0 = P * P, h1 = 2 * P * P1, h2 = 2 * (P1 * P1 + P * P2), h3 = 2 * (3 * P1 * P2 + P * P3);
    A += b.ma[0] - (b.ma[0] * h0 + X * (b.ma[1] * h1 + X * (b.ma[2] * h2 / 2 + X * b.ma[3] * h3 / 6)));
  }
  return A;
}

}  // namespace asperity
