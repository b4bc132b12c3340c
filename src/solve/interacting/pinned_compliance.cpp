#include "solve/interacting/pinned_compliance.hpp"

#include <omp.h>

#include <algorithm>
#include <cstring>

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
// Removals kept aside (as G − Σ u uᵀ/d) before they are folded into the stored triangle in one
// pass: each fold reads and writes G once instead of once per removal.
constexpr std::size_t kDeferredRemovals = 8;

// Four doubles as one value (GCC's vector extensions): one AVX2 register, or two SSE2 / NEON
// registers. The arithmetic is lane by lane and this file is compiled without fused multiply-add
// (CMakeLists.txt), so both forms give the same bits.
using Quad = double __attribute__((vector_size(32)));
using Half = double __attribute__((vector_size(16)));
struct HalfPair {
  Half lo, hi;
};
inline HalfPair operator+(HalfPair a, HalfPair b) { return {a.lo + b.lo, a.hi + b.hi}; }
inline HalfPair operator*(HalfPair a, HalfPair b) { return {a.lo * b.lo, a.hi * b.hi}; }
inline HalfPair& operator+=(HalfPair& a, HalfPair b) { return a = a + b; }
template <class V> inline V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class V> inline void store(double* p, V v) { std::memcpy(p, &v, sizeof v); }
template <> inline HalfPair load<HalfPair>(const double* p) { return {load<Half>(p), load<Half>(p + 2)}; }
template <> inline void store<HalfPair>(double* p, HalfPair v) {
  store(p, v.lo);
  store(p + 2, v.hi);
}
template <class V> inline V splat(double x) {
  const double four[4] = {x, x, x, x};
  return load<V>(four);
}
inline double sum(Quad v) { return (v[0] + v[1]) + (v[2] + v[3]); }
inline double sum(HalfPair v) { return (v.lo[0] + v.lo[1]) + (v.hi[0] + v.hi[1]); }

// One row r of the stored triangle from column c on (the columns before, from r, already in
// t1, t2): its sums in four lanes plus the tail, into p[r]; its transposed products into p[c..].
template <class V>
[[gnu::always_inline]] inline void one_row(const double* __restrict A, std::size_t r, std::size_t c, std::size_t n,
                                           double t1, double t2, const double* __restrict w1,
                                           const double* __restrict w2, double* __restrict p1, double* __restrict p2) {
  const double a1 = w1[r], a2 = w2[r];
  const V va1 = splat<V>(a1), va2 = splat<V>(a2);
  V s1 = splat<V>(0.0), s2 = s1;
  for (; c + 4 <= n; c += 4) {
    const V ga = load<V>(A + c);
    s1 += ga * load<V>(w1 + c);
    s2 += ga * load<V>(w2 + c);
    store(p1 + c, load<V>(p1 + c) + ga * va1);
    store(p2 + c, load<V>(p2 + c) + ga * va2);
  }
  double e1 = 0, e2 = 0;
  for (; c < n; ++c) {
    e1 += A[c] * w1[c];
    e2 += A[c] * w2[c];
    p1[c] += A[c] * a1;
    p2[c] += A[c] * a2;
  }
  p1[r] += t1 + (sum(s1) + e1);
  p2[r] += t2 + (sum(s2) + e2);
}

// Rows [r0, r1) of the stored triangle times (w1, w2): row r's own sums into p[r], its entries'
// transposed products into p[c > r]. Two rows at a time: each load of w and each update of p
// serves two rows of G (the loop is bound by loads and stores, not arithmetic). Every sum has one
// fixed order (four lanes, combined pairwise): the same bits from either form, on any number of
// threads. Each p[c] takes its rows' terms in row order, as a row-by-row loop would.
template <class V>
[[gnu::always_inline]] inline void product_rows(const double* __restrict G, std::size_t N, std::size_t n, std::size_t r0,
                                                std::size_t r1, const double* __restrict w1, const double* __restrict w2,
                                                double* __restrict p1, double* __restrict p2) {
  std::size_t r = r0;
  for (; r + 1 < r1; r += 2) {
    const double* __restrict A = G + r * N;
    const double* __restrict Bw = A + N;
    const double a1 = w1[r], a2 = w2[r], b1 = w1[r + 1], b2 = w2[r + 1];
    // Row r's diagonal and its entry at r + 1 (row r + 1 starts at its diagonal there).
    const double g = A[r + 1];
    const double tA1 = A[r] * a1 + g * w1[r + 1], tA2 = A[r] * a2 + g * w2[r + 1];
    p1[r + 1] += g * a1;
    p2[r + 1] += g * a2;
    const double tB1 = Bw[r + 1] * b1, tB2 = Bw[r + 1] * b2;
    const V va1 = splat<V>(a1), va2 = splat<V>(a2), vb1 = splat<V>(b1), vb2 = splat<V>(b2);
    V sA1 = splat<V>(0.0), sA2 = sA1, sB1 = sA1, sB2 = sA1;
    std::size_t c = r + 2;
    for (; c + 4 <= n; c += 4) {
      const V ga = load<V>(A + c), gb = load<V>(Bw + c), x1 = load<V>(w1 + c), x2 = load<V>(w2 + c);
      sA1 += ga * x1;
      sA2 += ga * x2;
      sB1 += gb * x1;
      sB2 += gb * x2;
      store(p1 + c, (load<V>(p1 + c) + ga * va1) + gb * vb1);
      store(p2 + c, (load<V>(p2 + c) + ga * va2) + gb * vb2);
    }
    double eA1 = 0, eA2 = 0, eB1 = 0, eB2 = 0;
    for (; c < n; ++c) {
      const double ga = A[c], gb = Bw[c];
      eA1 += ga * w1[c];
      eA2 += ga * w2[c];
      eB1 += gb * w1[c];
      eB2 += gb * w2[c];
      p1[c] = (p1[c] + ga * a1) + gb * b1;
      p2[c] = (p2[c] + ga * a2) + gb * b2;
    }
    p1[r] += tA1 + (sum(sA1) + eA1);
    p2[r] += tA2 + (sum(sA2) + eA2);
    p1[r + 1] += tB1 + (sum(sB1) + eB1);
    p2[r + 1] += tB2 + (sum(sB2) + eB2);
  }
  if (r < r1) {  // an odd row left: alone, the same way
    const double* __restrict A = G + r * N;
    one_row<V>(A, r, r + 1, n, A[r] * w1[r], A[r] * w2[r], w1, w2, p1, p2);
  }
}

using ProductRows = void (*)(const double*, std::size_t, std::size_t, std::size_t, std::size_t, const double*,
                             const double*, double*, double*);
// The same rows one at a time, for CPUs with 16-byte vectors (SSE2, NEON), where two rows' sums
// would not fit in the registers. Each row's sum is grouped exactly as in product_rows (a row
// opening a pair takes its entry at r + 1 apart, as product_rows does), and each p[c] takes the
// same terms in the same order: the same bits.
void product_rows_portable(const double* __restrict G, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1,
                           const double* __restrict w1, const double* __restrict w2, double* __restrict p1,
                           double* __restrict p2) {
  for (std::size_t r = r0; r < r1; ++r) {
    const double* __restrict A = G + r * N;
    const double a1 = w1[r], a2 = w2[r];
    if ((r - r0) % 2 == 0 && r + 1 < r1) {  // opens a pair
      const double g = A[r + 1];
      p1[r + 1] += g * a1;
      p2[r + 1] += g * a2;
      one_row<HalfPair>(A, r, r + 2, n, A[r] * a1 + g * w1[r + 1], A[r] * a2 + g * w2[r + 1], w1, w2, p1, p2);
    } else {
      one_row<HalfPair>(A, r, r + 1, n, A[r] * a1, A[r] * a2, w1, w2, p1, p2);
    }
  }
}
#if defined(__x86_64__)
// The same rows with AVX2 (x86-64-v3: every x86 CPU since about 2013), chosen at run time.
__attribute__((target("arch=x86-64-v3"))) void product_rows_avx2(const double* G, std::size_t N, std::size_t n,
                                                                   std::size_t r0, std::size_t r1, const double* w1,
                                                                   const double* w2, double* p1, double* p2) {
  product_rows<Quad>(G, N, n, r0, r1, w1, w2, p1, p2);
}
ProductRows product_rows_for_this_cpu() {
  return __builtin_cpu_supports("x86-64-v3") ? product_rows_avx2 : product_rows_portable;
}
#else
ProductRows product_rows_for_this_cpu() { return product_rows_portable; }
#endif

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
  for (const Deferred& u : deferred_) {  // − Σ u (uᵀ w)/d, w zero outside the columns
    double c1 = 0, c2 = 0;
    for (std::size_t q : columns) c1 += u.u[q] * w1[q], c2 += u.u[q] * w2[q];
    c1 /= u.d, c2 /= u.d;
    for (std::size_t r = 0; r < n; ++r) y1[r] -= u.u[r] * c1, y2[r] -= u.u[r] * c2;
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
  static const ProductRows rows = product_rows_for_this_cpu();  // the CPU does not change
#pragma omp parallel for schedule(dynamic, 1) if (n * n > 2 * kParallelWork)
  for (std::size_t b = 0; b < B; ++b) {
    double* p1 = P + 2 * b * n;
    double* p2 = p1 + n;
    std::fill(p1 + edge[b], p1 + n, 0.0);
    std::fill(p2 + edge[b], p2 + n, 0.0);
    rows(G, N, n, edge[b], edge[b + 1], w1.data(), w2.data(), p1, p2);
  }
  for (std::size_t r = 0; r < n; ++r) {
    double s1 = 0, s2 = 0;
    for (std::size_t b = 0; b < B && edge[b] <= r; ++b) s1 += P[2 * b * n + r], s2 += P[(2 * b + 1) * n + r];
    y1[r] = s1;
    y2[r] = s2;
  }
  for (const Deferred& u : deferred_) {  // − Σ u (uᵀ w)/d
    double c1 = 0, c2 = 0;
    for (std::size_t r = 0; r < n; ++r) c1 += u.u[r] * w1[r], c2 += u.u[r] * w2[r];
    c1 /= u.d, c2 /= u.d;
    for (std::size_t r = 0; r < n; ++r) y1[r] -= u.u[r] * c1, y2[r] -= u.u[r] * c2;
  }
}

std::vector<double> PinnedCompliance::row(std::size_t q) const {
  std::vector<double> g(n_);
  for (std::size_t r = 0; r < q; ++r) g[r] = G_[r * N_ + q];  // column q of the triangle
  for (std::size_t s = q; s < n_; ++s) g[s] = G_[q * N_ + s];
  // The removals not yet folded, in order: each entry takes the same operations as fold() would
  // apply to it (the entry of the triangle of row min(r, q), column max(r, q)).
  for (const Deferred& u : deferred_)
    for (std::size_t r = 0; r < n_; ++r) g[r] -= (r <= q ? u.u[r] / u.d * u.u[q] : u.u[q] / u.d * u.u[r]);
  return g;
}

void PinnedCompliance::fold() {
  if (deferred_.empty()) return;
  const std::size_t n = n_, N = N_;
  double* G = G_.data();
  // Entry (r, s ≥ r) takes each removal in order, as the removals one by one would.
#pragma omp parallel for schedule(dynamic, 64) if (n * n > 2 * kParallelWork)
  for (std::size_t r = 0; r < n; ++r) {
    double* row = G + r * N;
    for (const Deferred& u : deferred_) {
      const double w = u.u[r] / u.d;
      const double* us = u.u.data();
      for (std::size_t s = r; s < n; ++s) row[s] -= w * us[s];
    }
  }
  deferred_.clear();
}

void PinnedCompliance::remove(std::size_t q, double f_sl) {
  const std::size_t n = n_, N = N_, i = idx_[q];
  const std::vector<double> g = row(q);
  const double gqq = g[q];
  if (nl_[q]) --n_nl_;
  double* G = G_.data();
  // G' = G − g gᵀ/g_qq (the inverse of M without row and column q; they become 0), kept aside
  // until kDeferredRemovals of them are folded into the stored triangle together.
  deferred_.push_back(Deferred{g, gqq});
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
    for (Deferred& u : deferred_) u.u[q] = u.u[last];
  }
  for (Deferred& u : deferred_) u.u.pop_back();
  pos_[i] = npos;
  n_ = last;
  ++rank_one_;
  if (deferred_.size() >= kDeferredRemovals) fold();
  // Rank-one updates accumulate rounding: start afresh after about N of them.
  if (++updates_since_rebuild_ > static_cast<std::int64_t>(std::max<std::size_t>(N_, 64)) && n_ > 0) rebuild();
}

std::size_t PinnedCompliance::add(std::size_t i, bool nonlinear) {
  deferred_.clear();  // G is stale until rebuild(), which starts from C and D
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
  deferred_.clear();  // G starts afresh from C and D
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
