#pragma once
// A second model of the PinnedOperator concept (solve/interacting/pinned_operator.hpp), for the
// operator probe (ASPERITY_PROBES): G = (D + C_PP)⁻¹ never formed, each product G w a conjugate-
// gradient solve of (D + C_PP) y = w whose matrix product is the precorrected FFT
// (solve/interacting/fft_coupling.hpp: O(N log N) a product, O(N) memory, 1–4e-9 of the dense
// product at its defaults). Preconditioned by D (Jacobi). A slip costs no rank-one update of G,
// only the two solves of a0 = G 1 and b0 = −G h. Approximate: every entry within the FFT product's
// error and the CG residual (1e-10 relative); docs/performance.md compares it with the dense
// operator inside the chord solver.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "physics/contact_law.hpp"
#include "physics/elastic_interaction.hpp"
#include "solve/core/problem.hpp"
#include "solve/interacting/fft_coupling.hpp"
#include "solve/interacting/pinned_operator.hpp"

namespace asperity {

class KrylovPinnedOperator {
 public:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  static constexpr double kResidual = 1e-10;  // CG stops at this relative residual

  struct PassBudget {  // the shape the chord solver fills; every pass here is "exact"
    std::vector<double> y1;
    double y2 = 0;
  };
  enum class Pass { exact };

  KrylovPinnedOperator(const Problem& problem, std::vector<double> reference, bool nonlinear,
                       std::size_t /*single_from*/)
      : p_(problem),
        fft_(problem),
        N_(problem.size()),
        n_(problem.size()),
        idx_(N_),
        pos_(N_),
        D_(std::move(reference)),
        h_(N_, 0.0),
        a0_(N_, 0.0),
        b0_(N_, 0.0),
        nl_(N_, nonlinear ? 1 : 0),
        n_nl_(nonlinear ? N_ : 0),
        radius_(N_) {
    std::iota(idx_.begin(), idx_.end(), std::uint32_t{0});
    std::iota(pos_.begin(), pos_.end(), std::size_t{0});
    for (std::size_t i = 0; i < N_; ++i) radius_[i] = disc_radius(problem.A0[i]);
    rebuild();
  }

  std::size_t size() const { return n_; }
  std::size_t junction(std::size_t q) const { return idx_[q]; }
  std::size_t position(std::size_t i) const { return pos_[i]; }
  bool nonlinear(std::size_t q) const { return nl_[q] != 0; }
  std::size_t n_nonlinear() const { return n_nl_; }
  double reference(std::size_t q) const { return D_[q]; }
  double a0(std::size_t q) const { return a0_[q]; }
  double b0(std::size_t q) const { return b0_[q]; }
  double coupling(std::size_t i, std::size_t j) const {  // exact C_ij [m/N], junctions
    if (i == j) return 0.0;
    return disc_compliance(p_.x[i] - p_.x[j], p_.y[i] - p_.y[j], radius_[i], radius_[j], p_.law.E, p_.law.nu,
                           p_.interaction_weighting);
  }
  std::vector<double> row(std::size_t q) {
    std::vector<double> e(n_, 0.0), y(n_, 0.0);
    e[q] = 1.0;
    solve(e, y);
    return y;
  }
  // y = G w by CG, warm-started from y's input (the last pass's image: a good guess).
  void apply(const std::vector<std::size_t>&, const std::vector<double>& w1, const std::vector<double>& w2,
             std::vector<double>& y1, std::vector<double>& y2) {
    solve(w1, y1);
    solve(w2, y2);
  }
  Pass apply(const std::vector<std::size_t>& columns, const std::vector<double>& w1, const std::vector<double>& w2,
             std::vector<double>& y1, std::vector<double>& y2, const PassBudget&) {
    apply(columns, w1, w2, y1, y2);
    return Pass::exact;
  }
  bool single_kept() const { return false; }

  void set_reference(std::size_t q, double D) { D_[q] = D; }
  void rebuild() {
    ++rebuilds_;
    load_vectors();
  }
  void remove(std::size_t q, double f_slip) {
    const std::size_t i = idx_[q], last = n_ - 1;
    if (nl_[q]) --n_nl_;
    for (std::size_t r = 0; r < n_; ++r) h_[r] += coupling(idx_[r], i) * f_slip;
    if (q != last) {
      idx_[q] = idx_[last], D_[q] = D_[last], h_[q] = h_[last], nl_[q] = nl_[last];
      a0_[q] = a0_[last], b0_[q] = b0_[last];
      pos_[idx_[q]] = q;
    }
    pos_[i] = npos;
    n_ = last;
    ++rank_one_;
    load_vectors();  // warm-started from the old vectors, the removed entry dropped
  }
  std::size_t add(std::size_t i, bool nonlinear) {
    const std::size_t q = n_++;
    idx_[q] = static_cast<std::uint32_t>(i);
    pos_[i] = q;
    nl_[q] = nonlinear ? 1 : 0;
    if (nonlinear) ++n_nl_;
    return q;
  }
  void set_anchors(const std::vector<double>& anchor_m) {
    for (std::size_t q = 0; q < n_; ++q) h_[q] = anchor_m[idx_[q]];
  }

  std::int64_t rebuilds() const { return rebuilds_; }
  std::int64_t rank_one_updates() const { return rank_one_; }
  std::int64_t products() const { return products_; }  // FFT products, for the probe

 private:
  // a0 = G 1, b0 = −G h.
  void load_vectors() {
    std::vector<double> one(n_, 1.0), a(a0_.begin(), a0_.begin() + n_), b(n_), mh(n_);
    for (std::size_t q = 0; q < n_; ++q) b[q] = -b0_[q], mh[q] = h_[q];
    solve(one, a);
    solve(mh, b);
    for (std::size_t q = 0; q < n_; ++q) a0_[q] = a[q], b0_[q] = -b[q];
  }
  // out = (D + C_PP) w over the positions.
  void product(const std::vector<double>& w, std::vector<double>& out) {
    std::vector<double> x(N_, 0.0), y(N_);
    for (std::size_t q = 0; q < n_; ++q) x[idx_[q]] = w[q];
    fft_.apply(x.data(), y.data());
    ++products_;
    out.resize(n_);
    for (std::size_t q = 0; q < n_; ++q) out[q] = D_[q] * w[q] + y[idx_[q]];
  }
  // Preconditioned CG on (D + C_PP) y = b from y (resized to n_ if needed), preconditioner D⁻¹.
  void solve(const std::vector<double>& b, std::vector<double>& y) {
    const std::size_t n = n_;
    y.resize(n);
    double bb = 0;
    for (std::size_t q = 0; q < n; ++q) bb += b[q] * b[q];
    if (bb == 0) {
      std::fill(y.begin(), y.end(), 0.0);
      return;
    }
    std::vector<double> r(n), z(n), d(n), Md(n);
    product(y, Md);
    double rz = 0, rr = 0;
    for (std::size_t q = 0; q < n; ++q) r[q] = b[q] - Md[q], z[q] = r[q] / D_[q], d[q] = z[q], rz += r[q] * z[q];
    for (std::size_t q = 0; q < n; ++q) rr += r[q] * r[q];
    const double stop = kResidual * kResidual * bb;
    for (int it = 0; it < 1000 && rr > stop; ++it) {
      product(d, Md);
      double dMd = 0;
      for (std::size_t q = 0; q < n; ++q) dMd += d[q] * Md[q];
      const double alpha = rz / dMd;
      double rz2 = 0;
      rr = 0;
      for (std::size_t q = 0; q < n; ++q) {
        y[q] += alpha * d[q];
        r[q] -= alpha * Md[q];
        z[q] = r[q] / D_[q];
        rz2 += r[q] * z[q];
        rr += r[q] * r[q];
      }
      for (std::size_t q = 0; q < n; ++q) d[q] = z[q] + (rz2 / rz) * d[q];
      rz = rz2;
    }
  }

  const Problem& p_;
  FftCoupling fft_;
  std::size_t N_ = 0, n_ = 0;
  std::vector<std::uint32_t> idx_;
  std::vector<std::size_t> pos_;
  std::vector<double> D_, h_, a0_, b0_;
  std::vector<std::uint8_t> nl_;
  std::size_t n_nl_ = 0;
  std::vector<double> radius_;
  std::int64_t rebuilds_ = 0, rank_one_ = 0, products_ = 0;
};

static_assert(PinnedOperator<KrylovPinnedOperator>);

}  // namespace asperity
