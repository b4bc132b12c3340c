#include "solve/interacting/pinned_compliance.hpp"

#include <omp.h>

#include <algorithm>

#include "solve/interacting/solver_failure.hpp"

// LAPACK (Debian liblapack-dev, or any optimised implementation behind the same symbols):
// Cholesky factorisation and inverse of a symmetric positive definite matrix, in place.
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

namespace asperity {

namespace {

// Work below which a loop over G stays on one thread (thread start-up costs more).
constexpr std::size_t kParallelWork = 200000;

}  // namespace

PinnedCompliance::PinnedCompliance(const Problem& problem, std::vector<double> reference, bool nonlinear)
    : N_(problem.size()),
      n_(problem.size()),
      C_(interaction_matrix(problem)),
      G_(problem.size() * problem.size(), 0.0),
      D_(std::move(reference)) {
  idx_.resize(N_);
  pos_.resize(N_);
  h_.assign(N_, 0.0);
  a0_.assign(N_, 0.0);
  b0_.assign(N_, 0.0);
  nl_.assign(N_, nonlinear ? 1 : 0);
  for (std::size_t i = 0; i < N_; ++i) {
    idx_[i] = static_cast<std::uint32_t>(i);
    pos_[i] = i;
  }
  n_nl_ = nonlinear ? N_ : 0;
  rebuild();
}

void PinnedCompliance::apply(const std::vector<std::size_t>& columns, const std::vector<double>& w1,
                             const std::vector<double>& w2, std::vector<double>& y1, std::vector<double>& y2) const {
  const std::size_t n = n_, N = N_;
  std::fill(y1.begin(), y1.end(), 0.0);
  std::fill(y2.begin(), y2.end(), 0.0);
  const double* G = G_.data();
  // Split by output range: each thread owns its rows of y, so the sums keep one order.
#pragma omp parallel if (n * columns.size() > kParallelWork)
  {
    const std::size_t T = static_cast<std::size_t>(omp_get_num_threads());
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t lo = n * t / T, hi = n * (t + 1) / T;
    double* o1 = y1.data();
    double* o2 = y2.data();
    for (std::size_t q : columns) {
      const double v1 = w1[q], v2 = w2[q];
      const double* gq = G + q * N;
      for (std::size_t r = lo; r < hi; ++r) {
        o1[r] += v1 * gq[r];
        o2[r] += v2 * gq[r];
      }
    }
  }
}

std::vector<double> PinnedCompliance::row(std::size_t q) const {
  return std::vector<double>(G_.begin() + static_cast<std::ptrdiff_t>(q * N_),
                             G_.begin() + static_cast<std::ptrdiff_t>(q * N_ + n_));
}

void PinnedCompliance::remove(std::size_t q, double f_sl) {
  const std::size_t n = n_, N = N_, i = idx_[q];
  const std::vector<double> g = row(q);
  const double gqq = g[q];
  if (nl_[q]) --n_nl_;
  double* G = G_.data();
  // G' = G − g gᵀ/g_qq (the inverse of M without row and column q); rows q, col q become 0.
#pragma omp parallel for schedule(static) if (n * n > kParallelWork)
  for (std::size_t r = 0; r < n; ++r) {
    const double w = g[r] / gqq;
    double* row = G + r * N;
    for (std::size_t s = 0; s < n; ++s) row[s] -= w * g[s];
  }
  // a0' = G'1, b0' = −G'h' with h' = h + C_{·i} f_sl; G'C_{·i} = −g/g_qq (from G M = I).
  const double a0q = a0_[q], b0q = b0_[q];
  for (std::size_t r = 0; r < n; ++r) {
    a0_[r] -= g[r] * a0q / gqq;
    b0_[r] += g[r] * (f_sl - b0q) / gqq;
    h_[r] += C_(idx_[r], i) * f_sl;
  }
  // The last position moves into q.
  const std::size_t last = n - 1;
  if (q != last) {
    for (std::size_t s = 0; s < n; ++s) G[q * N + s] = G[last * N + s];
    for (std::size_t r = 0; r < n; ++r) G[r * N + q] = G[r * N + last];
    idx_[q] = idx_[last];
    D_[q] = D_[last];
    h_[q] = h_[last];
    a0_[q] = a0_[last];
    b0_[q] = b0_[last];
    nl_[q] = nl_[last];
    pos_[idx_[q]] = q;
  }
  pos_[i] = npos;
  n_ = last;
  ++rank_one_;
  // Rank-one updates accumulate rounding: start afresh after about N of them.
  if (++updates_since_rebuild_ > static_cast<std::int64_t>(std::max<std::size_t>(N_, 64)) && n_ > 0) rebuild();
}

std::size_t PinnedCompliance::add(std::size_t i, bool nonlinear) {
  const std::size_t q = n_++;
  idx_[q] = static_cast<std::uint32_t>(i);
  pos_[i] = q;
  nl_[q] = nonlinear ? 1 : 0;
  if (nonlinear) ++n_nl_;
  return q;
}

void PinnedCompliance::set_anchors(const std::vector<double>& anchor_m) {
  for (std::size_t q = 0; q < n_; ++q) h_[q] = anchor_m[idx_[q]];
}

void PinnedCompliance::rebuild() {
  const std::size_t n = n_, N = N_;
  if (n == 0) return;
  double* G = G_.data();
  for (std::size_t r = 0; r < n; ++r) {
    const std::size_t i = idx_[r];
    for (std::size_t s = 0; s < n; ++s) G[r * N + s] = C_(i, idx_[s]);
    G[r * N + r] = D_[r];
  }
  // Column-major LAPACK on the row-major buffer sees the same symmetric matrix; 'L' there is
  // our upper triangle.
  const int ni = static_cast<int>(n), lda = static_cast<int>(N);
  int info = 0;
  dpotrf_("L", &ni, G, &lda, &info);
  if (info != 0) interacting_solver_failure("the pinned junctions' compliance matrix is not positive definite", 0.0);
  dpotri_("L", &ni, G, &lda, &info);
  if (info != 0) interacting_solver_failure("the pinned junctions' compliance matrix is singular", 0.0);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t s = 0; s < r; ++s) G[r * N + s] = G[s * N + r];
  // a0 = G 1, b0 = −G h.
#pragma omp parallel for schedule(static) if (n * n > kParallelWork)
  for (std::size_t r = 0; r < n; ++r) {
    const double* row = G + r * N;
    double a = 0, b = 0;
    for (std::size_t s = 0; s < n; ++s) a += row[s], b -= row[s] * h_[s];
    a0_[r] = a;
    b0_[r] = b;
  }
  updates_since_rebuild_ = 0;
  ++rebuilds_;
}

}  // namespace asperity
