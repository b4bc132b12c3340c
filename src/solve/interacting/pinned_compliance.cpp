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
// Row blocks of the symmetric product: fixed, so its sums do not depend on the thread count.
constexpr std::size_t kProductBlocks = 16;
// Below n / kFewColumns weighted columns, the product reads those columns alone (strided above
// the diagonal, about 8 times the cost of a sequential read: break-even near n / 9).
constexpr std::size_t kFewColumns = 10;
// Pinned sets below this size are factorised and inverted by LAPACK on one thread.
constexpr std::size_t kParallelLapack = 2000;

}  // namespace

PinnedCompliance::PinnedCompliance(const Problem& problem, std::vector<double> reference, bool nonlinear)
    : N_(problem.size()),
      n_(problem.size()),
      G_(problem.size() * problem.size(), 0.0),
      D_(std::move(reference)) {
  fill_interaction_lower(problem, G_.data(), N_);
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
  // Many columns (before the first peak, every pinned junction): the product over the whole
  // stored triangle, the weights being zero elsewhere; it reads each stored entry once (half of
  // G, where a row-by-row product over the full matrix reads all of it) and uses it twice.
  if (columns.size() * kFewColumns >= n) return symmetric_product(w1, w2, y1, y2);
  // A few columns (after slips and repins, the junctions never slipped): those columns alone,
  // from the triangle's column q above the diagonal and its row q from the diagonal on.
  std::fill(y1.begin(), y1.begin() + static_cast<std::ptrdiff_t>(n), 0.0);
  std::fill(y2.begin(), y2.begin() + static_cast<std::ptrdiff_t>(n), 0.0);
  const double* G = G_.data();
  for (std::size_t q : columns) {
    const double v1 = w1[q], v2 = w2[q];
    for (std::size_t r = 0; r < q; ++r) {
      const double g = G[r * N + q];
      y1[r] += g * v1;
      y2[r] += g * v2;
    }
    const double* row = G + q * N;
    for (std::size_t s = q; s < n; ++s) {
      y1[s] += row[s] * v1;
      y2[s] += row[s] * v2;
    }
  }
}

void PinnedCompliance::symmetric_product(const std::vector<double>& w1, const std::vector<double>& w2,
                                         std::vector<double>& y1, std::vector<double>& y2) const {
  const std::size_t n = n_, N = N_;
  // Fixed row blocks of about equal work (row r holds n − r stored entries), each summing into
  // its own partial vectors, added in block order: the same sums in the same order whatever the
  // number of threads.
  // (About 128 rows a block: fewer blocks for a small matrix, whose partial sums would cost as much
  // as the product itself.)
  const std::size_t B = std::clamp<std::size_t>(n / 128, 1, kProductBlocks);
  std::vector<std::size_t> edge(B + 1, n);
  edge[0] = 0;
  const double total = 0.5 * static_cast<double>(n) * static_cast<double>(n + 1);
  for (std::size_t b = 1, r = 0; b < B; ++b) {
    const double want = total * static_cast<double>(b) / static_cast<double>(B);
    // work before row r: r n − r(r − 1)/2
    while (r < n && static_cast<double>(r) * static_cast<double>(n) - 0.5 * static_cast<double>(r) * (static_cast<double>(r) - 1.0) < want) ++r;
    edge[b] = r;
  }
  partial_.resize(2 * B * n);  // block b writes (and zeroes) only its entries from edge[b] on
  const double* G = G_.data();
  double* P = partial_.data();
#pragma omp parallel for schedule(dynamic, 1) if (n * n > 2 * kParallelWork)
  for (std::size_t b = 0; b < B; ++b) {
    double* p1 = P + 2 * b * n;
    double* p2 = p1 + n;
    std::fill(p1 + edge[b], p1 + n, 0.0);
    std::fill(p2 + edge[b], p2 + n, 0.0);
    for (std::size_t r = edge[b]; r < edge[b + 1]; ++r) {
      const double* row = G + r * N;
      const double u1 = w1[r], u2 = w2[r];
      double t1 = row[r] * u1, t2 = row[r] * u2;
      // Vectorised (the sums of a row in SIMD lanes: one fixed order for a given build).
#pragma omp simd reduction(+ : t1, t2)
      for (std::size_t c = r + 1; c < n; ++c) {
        const double g = row[c];
        t1 += g * w1[c];
        t2 += g * w2[c];
        p1[c] += g * u1;
        p2[c] += g * u2;
      }
      p1[r] += t1;
      p2[r] += t2;
    }
  }
  for (std::size_t r = 0; r < n; ++r) {
    double s1 = 0, s2 = 0;
    for (std::size_t b = 0; b < B && edge[b] <= r; ++b) s1 += P[2 * b * n + r], s2 += P[(2 * b + 1) * n + r];
    y1[r] = s1;
    y2[r] = s2;
  }
}

std::vector<double> PinnedCompliance::row(std::size_t q) const {
  std::vector<double> g(n_);
  for (std::size_t r = 0; r < q; ++r) g[r] = G_[r * N_ + q];  // column q of the triangle
  for (std::size_t s = q; s < n_; ++s) g[s] = G_[q * N_ + s];
  return g;
}

void PinnedCompliance::remove(std::size_t q, double f_sl) {
  const std::size_t n = n_, N = N_, i = idx_[q];
  const std::vector<double> g = row(q);
  const double gqq = g[q];
  if (nl_[q]) --n_nl_;
  double* G = G_.data();
  // G' = G − g gᵀ/g_qq (the inverse of M without row and column q; they become 0), on the
  // stored triangle.
#pragma omp parallel for schedule(dynamic, 64) if (n * n > 2 * kParallelWork)
  for (std::size_t r = 0; r < n; ++r) {
    const double w = g[r] / gqq;
    double* row = G + r * N;
    for (std::size_t s = r; s < n; ++s) row[s] -= w * g[s];
  }
  // a0' = G'1, b0' = −G'h' with h' = h + C_{·i} f_sl; G'C_{·i} = −g/g_qq (from G M = I).
  const double a0q = a0_[q], b0q = b0_[q];
  for (std::size_t r = 0; r < n; ++r) {
    a0_[r] -= g[r] * a0q / gqq;
    b0_[r] += g[r] * (f_sl - b0q) / gqq;
    h_[r] += coupling(idx_[r], i) * f_sl;
  }
  // The last position moves into q.
  const std::size_t last = n - 1;
  if (q != last) {
    // Entry (q, ·) of the new matrix is entry (last, ·) of the old, all of them in the triangle's
    // column `last`: above q in column q, right of q in row q.
    for (std::size_t r = 0; r < q; ++r) G[r * N + q] = G[r * N + last];
    G[q * N + q] = G[last * N + last];
    for (std::size_t s = q + 1; s < last; ++s) G[q * N + s] = G[s * N + last];
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
    for (std::size_t s = r + 1; s < n; ++s) G[r * N + s] = coupling(i, idx_[s]);
    G[r * N + r] = D_[r];
  }
  // Column-major LAPACK on the row-major buffer sees the same symmetric matrix; 'L' there is
  // our upper triangle.
  const int ni = static_cast<int>(n), lda = static_cast<int>(N);
  int info = 0;
  // Below kParallelLapack, one thread: OpenBLAS's many short parallel regions gain little there,
  // and on a loaded machine their spinning barriers made a rebuild of n = 300 some 100 times
  // slower (0.49 → 14 s for a whole N = 300 run); the bits then do not depend on the thread count.
  const int threads = omp_get_max_threads();
  if (n < kParallelLapack) omp_set_num_threads(1);
  dpotrf_("L", &ni, G, &lda, &info);
  if (info == 0) dpotri_("L", &ni, G, &lda, &info);
  omp_set_num_threads(threads);
  if (info != 0) interacting_solver_failure("the pinned junctions' compliance matrix is not positive definite", 0.0);
  // a0 = G 1, b0 = −G h.
  const std::vector<double> ones(n, 1.0), h(h_.begin(), h_.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<double> a(n), b(n);
  symmetric_product(ones, h, a, b);
  for (std::size_t r = 0; r < n; ++r) a0_[r] = a[r], b0_[r] = -b[r];
  updates_since_rebuild_ = 0;
  ++rebuilds_;
}

}  // namespace asperity
