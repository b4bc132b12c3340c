#include "solve/interacting/pinned_compliance.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "solve/interacting/pinned_kernels.hpp"
#include "solve/interacting/solver_failure.hpp"

// LAPACK (Debian liblapack-dev, or any optimised implementation behind the same symbols):
// Cholesky factorisation and inverse of a symmetric positive definite matrix, in place.
extern "C" {
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info);
void dpotri_(const char* uplo, const int* n, double* a, const int* lda, int* info);
}

namespace asperity {

namespace {

// Row blocks of the symmetric product: fixed, so its sums do not depend on the thread count.
constexpr std::size_t kProductBlocks = 16;
// Below n / kFewColumns weighted columns, the product reads those columns alone (strided above
// the diagonal, about 8 times the cost of a sequential read: break-even near n / 9).
constexpr std::size_t kFewColumns = 10;
// Pinned sets below this size are factorised and inverted by LAPACK on one thread.
constexpr std::size_t kParallelLapack = 2000;
// Removals kept aside before a fold below n = large_from_ (kDeferredRemovals from there on,
// pinned_kernels.hpp).
constexpr std::size_t kDeferredRemovalsSmall = 8;

}  // namespace

PinnedCompliance::PinnedCompliance(const Problem& problem, std::vector<double> reference, bool nonlinear,
                                   std::size_t single_from)
    : N_(problem.size()),
      n_(problem.size()),
      large_from_(single_from),
      form_(kernel_form()),
      teams_(omp_get_max_threads()),
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
  if (N_ >= single_from) single_.S.resize(N_ * (N_ + 1) / 2);
  rebuild();
}

void PinnedCompliance::apply(const std::vector<std::size_t>& columns, const std::vector<double>& w1,
                             const std::vector<double>& w2, std::vector<double>& y1, std::vector<double>& y2) {
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

std::vector<std::size_t> PinnedCompliance::row_blocks() const {
  const std::size_t n = n_;
  // Blocks of about equal work (row r holds n − r stored entries), about 128 rows a block: fewer
  // blocks for a small matrix, whose partial sums would cost as much as the product itself.
  const std::size_t B = std::clamp<std::size_t>(n / 128, 1, kProductBlocks);
  std::vector<std::size_t> edge(B + 1, n);
  edge[0] = 0;
  const double total = 0.5 * static_cast<double>(n) * static_cast<double>(n + 1);
  for (std::size_t b = 1, r = 0; b < B; ++b) {
    const double want = total * static_cast<double>(b) / static_cast<double>(B);
    // work before row r: r n − r(r − 1)/2
    while (r < n && static_cast<double>(r) * static_cast<double>(n) -
                            0.5 * static_cast<double>(r) * (static_cast<double>(r) - 1.0) <
                        want)
      ++r;
    edge[b] = r;
  }
  return edge;
}

void PinnedCompliance::symmetric_product(const std::vector<double>& w1, const std::vector<double>& w2,
                                         std::vector<double>& y1, std::vector<double>& y2) {
  const ProductRows rows = product_rows_for(form_);
  triangle_product(rows, G_.data(), N_, n_, row_blocks(), partial_, w1, w2, y1, y2, teams_.product);
  subtract_deferred(w1, w2, y1, y2);
}

void PinnedCompliance::subtract_deferred(const std::vector<double>& w1, const std::vector<double>& w2,
                                         std::vector<double>& y1, std::vector<double>& y2) {
  // − Σ u (uᵀ w)/d, in order. All removals in one sweep over the positions for the dot products
  // (each a chain of its own: the chains overlap) and one for the updates: the same operations as
  // one removal at a time, so the same bits.
  const std::size_t n = n_, K = deferred_.size();
  if (K == 0) return;
  double c1[kDeferredRemovals] = {}, c2[kDeferredRemovals] = {};
  const double* u[kDeferredRemovals];
  for (std::size_t k = 0; k < K; ++k) u[k] = deferred_[k].u.data();
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t k = 0; k < K; ++k) c1[k] += u[k][r] * w1[r], c2[k] += u[k][r] * w2[r];
  for (std::size_t k = 0; k < K; ++k) c1[k] /= deferred_[k].d, c2[k] /= deferred_[k].d;
  const AdaptiveTeam::Region region(teams_.deferred, static_cast<double>(n) * static_cast<double>(K));
  const int threads = region.threads();
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t r = 0; r < n; ++r) {
    double v1 = y1[r], v2 = y2[r];
    for (std::size_t k = 0; k < K; ++k) v1 -= u[k][r] * c1[k], v2 -= u[k][r] * c2[k];
    y1[r] = v1, y2[r] = v2;
  }
}

PinnedCompliance::Pass PinnedCompliance::apply(const std::vector<std::size_t>& columns, const std::vector<double>& w1,
                                               const std::vector<double>& w2, std::vector<double>& y1,
                                               std::vector<double>& y2, const PassBudget& budget) {
  const std::size_t n = n_;
  if (!single_.usable || columns.size() * kFewColumns < n) {
    apply(columns, w1, w2, y1, y2);
    return Pass::exact;
  }
  const SingleProductRows single_rows = single_rows_for(form_);
  // Row r's error is Σ_j (T_rj − S_rj)(w_j − ref_j), so by Cauchy–Schwarz at most
  // ‖T_r − S_r‖₂ ‖w − ref‖₂, the first factor bounded as the copy was written (the rounding
  // errors themselves, exact in double: 0.35–0.37 of the 2⁻²⁴ ‖T_r‖₂ that rounding to nearest
  // allows at the median row of the stand-ins' G, 0.03–0.98 over the rows; the 2⁻¹⁵⁰ √n covers squares below the normal range): within the budget when
  // ‖w − ref‖₂ is within 1/ratio1 (for y1) and 1/ratio2 (for y2).
  const double tiny = std::ldexp(std::sqrt(static_cast<double>(n)), -150);
  double ratio1 = 0, largest = 0;
  for (std::size_t r = 0; r < n; ++r) {
    const double e = single_.row_error[r] + tiny;
    ratio1 = std::max(ratio1, e / budget.y1[r]);
    largest = std::max(largest, e);
  }
  const double ratio2 = largest / budget.y2;
  const auto within = [&](const std::vector<double>& r1, const std::vector<double>& r2) {
    return ratio1 * distance(w1, r1, n) <= 1.0 && ratio2 * distance(w2, r2, n) <= 1.0;
  };
  // A single pass; or an exact pass that becomes the new reference when the step from the last
  // pass shows the next passes would be within the budget of it (else a plain exact pass: a
  // reference costs half a pass more).
  Pass kind = Pass::exact;
  if (single_.valid && within(single_.ref1, single_.ref2))
    kind = Pass::single;
  else if (single_.has_last && within(single_.last1, single_.last2))
    kind = Pass::refresh;
  single_.last1.assign(w1.begin(), w1.begin() + static_cast<std::ptrdiff_t>(n));
  single_.last2.assign(w2.begin(), w2.begin() + static_cast<std::ptrdiff_t>(n));
  single_.has_last = true;
  if (kind == Pass::exact) {
    symmetric_product(w1, w2, y1, y2);
    return kind;
  }
  if (kind == Pass::single) {
    triangle_product(single_rows, single_.S.data(), N_, n, row_blocks(), partial_, w1, w2, y1, y2, teams_.single);
    for (std::size_t r = 0; r < n; ++r) y1[r] += single_.c1[r], y2[r] += single_.c2[r];
    subtract_deferred(w1, w2, y1, y2);
    ++single_.passes;
    return kind;
  }
  // Exact, and c = (T − S) w from the two products at this w: the new reference.
  const ProductRows rows = product_rows_for(form_);
  const std::vector<std::size_t> edge = row_blocks();
  std::vector<double> s1(n), s2(n);
  triangle_product(single_rows, single_.S.data(), N_, n, edge, partial_, w1, w2, s1, s2, teams_.single);
  triangle_product(rows, G_.data(), N_, n, edge, partial_, w1, w2, y1, y2, teams_.product);
  single_.c1.resize(n);
  single_.c2.resize(n);
  for (std::size_t r = 0; r < n; ++r) single_.c1[r] = y1[r] - s1[r], single_.c2[r] = y2[r] - s2[r];
  single_.ref1 = single_.last1;
  single_.ref2 = single_.last2;
  single_.valid = true;
  ++single_.refreshes;
  subtract_deferred(w1, w2, y1, y2);
  return kind;
}

void PinnedCompliance::finish_single(const std::vector<std::size_t>& edge, const std::vector<double>& own,
                                     const std::vector<double>& biggest) {
  const std::size_t n = n_;
  const double* P = partial_.data();
  single_.row_error.resize(n);
  for (std::size_t r = 0; r < n; ++r) {
    double sq = own[r];
    for (std::size_t b = 0; b + 1 < edge.size() && edge[b] <= r; ++b) sq += P[b * n + r];
    // ‖T_r − S_r‖₂: each sum of n squares is rounded by at most n units of 2⁻⁵³ of itself.
    single_.row_error[r] = std::sqrt(sq * (1.0 + 2e-16 * static_cast<double>(n + 2)));
  }
  // An entry beyond single precision's range would be infinite in S: no single passes then.
  single_.usable = *std::max_element(biggest.begin(), biggest.end()) < 1e38;
}

void PinnedCompliance::copy_single() {
  single_.valid = false;
  single_.usable = false;
  if (single_.S.empty()) return;
  write_rows(false);
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
  write_rows(true);
}

void PinnedCompliance::write_rows(bool removals) {
  const std::size_t n = n_, N = N_;
  // The single-precision copy is written as each row is done (one pass over the triangle, not two).
  const bool copy = !single_.S.empty();
  single_.valid = single_.usable = false;
  const std::vector<std::size_t> edge = row_blocks();
  const std::size_t B = edge.size() - 1;
  std::vector<const double*> u;
  std::vector<double> d;
  if (removals)
    for (const Deferred& r : deferred_) u.push_back(r.u.data()), d.push_back(r.d);
  const Removals rm{u.data(), d.data(), u.size()};
  std::vector<double> own(copy ? n : 0), biggest(B, 0.0);
  if (copy) partial_.resize(2 * B * n);
  double* P = partial_.data();
  const FoldRows rows = fold_rows_for(form_);
  // Entry (r, s ≥ r) takes each removal in order, as the removals one by one would. Row norms of
  // the symmetric T: entry (r, s > r) counts in rows r and s; the column parts go into per-block
  // sums, added in block order (the same bits on any number of threads).
  const AdaptiveTeam::Region region(teams_.fold, static_cast<double>(n) * static_cast<double>(n));
  const int threads = region.threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
  for (std::size_t b = 0; b < B; ++b) {
    CopySums cs;
    if (copy) {
      std::fill(P + b * n + edge[b], P + (b + 1) * n, 0.0);
      cs.S = single_.S.data();
      cs.col = P + b * n;
    }
    rows(G_.data(), N, n, edge[b], edge[b + 1], rm, cs, own.data());
    biggest[b] = cs.big;
  }
  if (removals) deferred_.clear();
  if (copy) finish_single(edge, own, biggest);
}

void PinnedCompliance::remove(std::size_t q, double f_sl) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n = n_, N = N_, i = idx_[q];
  const std::vector<double> g = row(q);
  const double gqq = g[q];
  if (nl_[q]) --n_nl_;
  double* G = G_.data();
  const std::size_t last = n - 1;
  if (single_.usable) {
    float* S = single_.S.data();
    // The reference product loses position q's column: c −= (T − S)_{·q} ref_q.
    if (single_.valid) {
      const double r1 = single_.ref1[q], r2 = single_.ref2[q];
      for (std::size_t r = 0; r < n; ++r) {
        const double t = r < q ? G[r * N + q] : G[q * N + r];
        const double e = t - static_cast<double>(static_cast<float>(t));
        single_.c1[r] -= e * r1;
        single_.c2[r] -= e * r2;
      }
      for (auto* v : {&single_.c1, &single_.c2, &single_.ref1, &single_.ref2}) {
        (*v)[q] = (*v)[last];
        v->pop_back();
      }
    }
    if (single_.has_last)
      for (auto* v : {&single_.last1, &single_.last2}) {
        (*v)[q] = (*v)[last];
        v->pop_back();
      }
    // The copy follows the triangle (below): row q's norm bound becomes that of the row moved
    // there; the others only lose an entry.
    if (q != last) {
      for (std::size_t r = 0; r < q; ++r) S[packed_row(r, N) + q] = S[packed_row(r, N) + last];
      S[packed_row(q, N) + q] = S[packed_row(last, N) + last];
      for (std::size_t s = q + 1; s < last; ++s) S[packed_row(q, N) + s] = S[packed_row(s, N) + last];
      single_.row_error[q] = single_.row_error[last];
    }
    single_.row_error.pop_back();
  } else {
    single_.valid = single_.has_last = false;
  }
  // G' = G − g gᵀ/g_qq (the inverse of M without row and column q; they become 0), kept aside
  // until kDeferredRemovals (below n = large_from_: kDeferredRemovalsSmall) of them are folded
  // into the stored triangle together.
  deferred_.push_back(Deferred{g, gqq});
  // a0' = G'1, b0' = −G'h' with h' = h + C_{·i} f_sl; G'C_{·i} = −g/g_qq (from G M = I).
  const double a0q = a0_[q], b0q = b0_[q];
  for (std::size_t r = 0; r < n; ++r) {
    a0_[r] -= g[r] * a0q / gqq;
    b0_[r] += g[r] * (f_sl - b0q) / gqq;
    h_[r] += coupling(idx_[r], i) * f_sl;
  }
  // The last position moves into q.
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
  remove_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (deferred_.size() >= (n_ >= large_from_ ? kDeferredRemovals : kDeferredRemovalsSmall)) fold();
  // Rank-one updates accumulate rounding: start afresh after about N of them.
  if (++updates_since_rebuild_ > static_cast<std::int64_t>(std::max<std::size_t>(N_, 64)) && n_ > 0) rebuild();
}

std::size_t PinnedCompliance::add(std::size_t i, bool nonlinear) {
  deferred_.clear();  // G is stale until rebuild(), which starts from C and D
  single_.valid = single_.usable = single_.has_last = false;
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
  const auto start = std::chrono::steady_clock::now();
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
  rebuild_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (info != 0) interacting_solver_failure("the pinned junctions' compliance matrix is not positive definite", 0.0);
  copy_single();
  // a0 = G 1, b0 = −G h.
  const std::vector<double> ones(n, 1.0), h(h_.begin(), h_.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<double> a(n), b(n);
  symmetric_product(ones, h, a, b);
  for (std::size_t r = 0; r < n; ++r) a0_[r] = a[r], b0_[r] = -b[r];
  updates_since_rebuild_ = 0;
  ++rebuilds_;
}

}  // namespace asperity
