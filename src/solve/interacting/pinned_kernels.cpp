#include "solve/interacting/pinned_kernels.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace asperity {

namespace {

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
template <class V>
inline V load(const double* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class V>
inline void store(double* p, V v) {
  std::memcpy(p, &v, sizeof v);
}
template <>
inline HalfPair load<HalfPair>(const double* p) {
  return {load<Half>(p), load<Half>(p + 2)};
}
template <>
inline void store<HalfPair>(double* p, HalfPair v) {
  store(p, v.lo);
  store(p + 2, v.hi);
}
template <class V>
inline V splat(double x) {
  const double four[4] = {x, x, x, x};
  return load<V>(four);
}
inline double sum(Quad v) { return (v[0] + v[1]) + (v[2] + v[3]); }
inline double sum(HalfPair v) { return (v.lo[0] + v.lo[1]) + (v.hi[0] + v.hi[1]); }

// The stored triangle's entries as four doubles: read as they are, or widened from single
// precision (the copy; exact, so every form reads the same values).
template <class V>
inline V entries(const double* p) {
  return load<V>(p);
}
using Single4 = float __attribute__((vector_size(16)));
template <class V>
inline V entries(const float* p);
template <>
inline Quad entries<Quad>(const float* p) {
  Single4 s;
  std::memcpy(&s, p, sizeof s);
  return __builtin_convertvector(s, Quad);
}
template <>
inline HalfPair entries<HalfPair>(const float* p) {
  return {Half{static_cast<double>(p[0]), static_cast<double>(p[1])},
          Half{static_cast<double>(p[2]), static_cast<double>(p[3])}};
}

// Rows of a triangle: row r's entry at column c ≥ r is rows(r)[c]. The stored triangle has rows
// N apart; the single-precision copy is packed (row r holds its N − r entries from the diagonal).
struct DoubleRows {
  const double* G;
  std::size_t N;
  const double* operator()(std::size_t r) const { return G + r * N; }
};
struct SingleRows {
  const float* S;
  std::size_t N;
  const float* operator()(std::size_t r) const { return S + packed_row(r, N); }
};

// One row r of the stored triangle from column c on (the columns before, from r, already in
// t1, t2): its sums in four lanes plus the tail, into p[r]; its transposed products into p[c..].
template <class V, class T>
[[gnu::always_inline]] inline void one_row(const T* __restrict A, std::size_t r, std::size_t c, std::size_t n,
                                           double t1, double t2, const double* __restrict w1,
                                           const double* __restrict w2, double* __restrict p1, double* __restrict p2) {
  const double a1 = w1[r], a2 = w2[r];
  const V va1 = splat<V>(a1), va2 = splat<V>(a2);
  V s1 = splat<V>(0.0), s2 = s1;
  for (; c + 4 <= n; c += 4) {
    const V ga = entries<V>(A + c);
    s1 += ga * load<V>(w1 + c);
    s2 += ga * load<V>(w2 + c);
    store(p1 + c, load<V>(p1 + c) + ga * va1);
    store(p2 + c, load<V>(p2 + c) + ga * va2);
  }
  double e1 = 0, e2 = 0;
  for (; c < n; ++c) {
    const double g = A[c];
    e1 += g * w1[c];
    e2 += g * w2[c];
    p1[c] += g * a1;
    p2[c] += g * a2;
  }
  p1[r] += t1 + (sum(s1) + e1);
  p2[r] += t2 + (sum(s2) + e2);
}

// Rows r .. r + 3 of product_rows (below).
template <class V, class Rows>
[[gnu::always_inline]] inline void four_rows(Rows rows, std::size_t n, std::size_t r, const double* __restrict w1,
                                             const double* __restrict w2, double* __restrict p1,
                                             double* __restrict p2) {
  const auto* __restrict A0 = rows(r);
  const auto* __restrict A1 = rows(r + 1);
  const auto* __restrict A2 = rows(r + 2);
  const auto* __restrict A3 = rows(r + 3);
  const double a0 = w1[r], a1 = w1[r + 1], a2 = w1[r + 2], a3 = w1[r + 3];
  const double b0 = w2[r], b1 = w2[r + 1], b2 = w2[r + 2], b3 = w2[r + 3];
  // The quad's diagonal block, row by row: row k's entries at columns r + k .. r + 3.
  double h1[4] = {}, h2[4] = {};
  {
    const decltype(A0) R[4] = {A0, A1, A2, A3};
    const double ak[4] = {a0, a1, a2, a3}, bk[4] = {b0, b1, b2, b3};
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t c = r + k; c < r + 4; ++c) {
        const double g = R[k][c];
        h1[k] += g * w1[c];
        h2[k] += g * w2[c];
        if (c > r + k) {
          p1[c] += g * ak[k];
          p2[c] += g * bk[k];
        }
      }
  }
  const V va0 = splat<V>(a0), va1 = splat<V>(a1), va2 = splat<V>(a2), va3 = splat<V>(a3);
  const V vb0 = splat<V>(b0), vb1 = splat<V>(b1), vb2 = splat<V>(b2), vb3 = splat<V>(b3);
  V s10 = splat<V>(0.0), s11 = s10, s12 = s10, s13 = s10, s20 = s10, s21 = s10, s22 = s10, s23 = s10;
  std::size_t c = r + 4;
  for (; c + 4 <= n; c += 4) {
    const V g0 = entries<V>(A0 + c), g1 = entries<V>(A1 + c), g2 = entries<V>(A2 + c), g3 = entries<V>(A3 + c);
    const V x1 = load<V>(w1 + c), x2 = load<V>(w2 + c);
    s10 += g0 * x1;
    s11 += g1 * x1;
    s12 += g2 * x1;
    s13 += g3 * x1;
    s20 += g0 * x2;
    s21 += g1 * x2;
    s22 += g2 * x2;
    s23 += g3 * x2;
    store(p1 + c, (((load<V>(p1 + c) + g0 * va0) + g1 * va1) + g2 * va2) + g3 * va3);
    store(p2 + c, (((load<V>(p2 + c) + g0 * vb0) + g1 * vb1) + g2 * vb2) + g3 * vb3);
  }
  double e1[4] = {}, e2[4] = {};
  for (; c < n; ++c) {
    const double g0 = A0[c], g1 = A1[c], g2 = A2[c], g3 = A3[c];
    e1[0] += g0 * w1[c], e1[1] += g1 * w1[c], e1[2] += g2 * w1[c], e1[3] += g3 * w1[c];
    e2[0] += g0 * w2[c], e2[1] += g1 * w2[c], e2[2] += g2 * w2[c], e2[3] += g3 * w2[c];
    p1[c] = (((p1[c] + g0 * a0) + g1 * a1) + g2 * a2) + g3 * a3;
    p2[c] = (((p2[c] + g0 * b0) + g1 * b1) + g2 * b2) + g3 * b3;
  }
  p1[r] += h1[0] + (sum(s10) + e1[0]);
  p1[r + 1] += h1[1] + (sum(s11) + e1[1]);
  p1[r + 2] += h1[2] + (sum(s12) + e1[2]);
  p1[r + 3] += h1[3] + (sum(s13) + e1[3]);
  p2[r] += h2[0] + (sum(s20) + e2[0]);
  p2[r + 1] += h2[1] + (sum(s21) + e2[1]);
  p2[r + 2] += h2[2] + (sum(s22) + e2[2]);
  p2[r + 3] += h2[3] + (sum(s23) + e2[3]);
}

// Rows r and r + 1 of product_rows (below).
template <class V, class Rows>
[[gnu::always_inline]] inline void two_rows(Rows rows, std::size_t n, std::size_t r, const double* __restrict w1,
                                            const double* __restrict w2, double* __restrict p1, double* __restrict p2) {
  const auto* __restrict A = rows(r);
  const auto* __restrict Bw = rows(r + 1);
  const double a1 = w1[r], a2 = w2[r], b1 = w1[r + 1], b2 = w2[r + 1];
  // Row r's diagonal and its entry at r + 1 (row r + 1 starts at its diagonal there).
  const double g = A[r + 1], gd = A[r], gb1 = Bw[r + 1];
  const double tA1 = gd * a1 + g * w1[r + 1], tA2 = gd * a2 + g * w2[r + 1];
  p1[r + 1] += g * a1;
  p2[r + 1] += g * a2;
  const double tB1 = gb1 * b1, tB2 = gb1 * b2;
  const V va1 = splat<V>(a1), va2 = splat<V>(a2), vb1 = splat<V>(b1), vb2 = splat<V>(b2);
  V sA1 = splat<V>(0.0), sA2 = sA1, sB1 = sA1, sB2 = sA1;
  std::size_t c = r + 2;
  for (; c + 4 <= n; c += 4) {
    const V ga = entries<V>(A + c), gb = entries<V>(Bw + c), x1 = load<V>(w1 + c), x2 = load<V>(w2 + c);
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

// Rows [r0, r1) of the stored triangle times (w1, w2): row r's own sums into p[r], its entries'
// transposed products into p[c > r]. Four rows at a time, then a pair and an odd row: each load
// of w and each update of p serves four rows of G (the loop is bound by loads and stores, not
// arithmetic; measured in docs/performance.md, "Four rows a pass"). Every sum has one fixed order
// (four lanes, combined pairwise; a row's entries left of the lanes, the quad's diagonal block,
// first): the same bits from every form (AVX-512, AVX2, 16-byte vectors), on any number of
// threads. Each
// p[c] takes its rows' terms in row order, as a row-by-row loop would.
template <class V, class Rows>
[[gnu::always_inline]] inline void product_rows(Rows rows, std::size_t n, std::size_t r0, std::size_t r1,
                                                const double* __restrict w1, const double* __restrict w2,
                                                double* __restrict p1, double* __restrict p2) {
  std::size_t r = r0;
  for (; r + 3 < r1; r += 4) four_rows<V>(rows, n, r, w1, w2, p1, p2);
  // Two or three rows left: a pair, then an odd row.
  if (r + 1 < r1) {
    two_rows<V>(rows, n, r, w1, w2, p1, p2);
    r += 2;
  }
  if (r < r1) {  // an odd row left: alone, the same way
    const auto* __restrict A = rows(r);
    const double gd = A[r];
    one_row<V>(A, r, r + 1, n, gd * w1[r], gd * w2[r], w1, w2, p1, p2);
  }
}

// The same rows with 16-byte vectors (SSE2, NEON: two registers a lane group), the same sums in
// the same order: the same bits.
void product_rows_portable(const double* G, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1,
                           const double* w1, const double* w2, double* p1, double* p2) {
  product_rows<HalfPair>(DoubleRows{G, N}, n, r0, r1, w1, w2, p1, p2);
}
void product_rows_single_portable(const float* S, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1,
                                  const double* w1, const double* w2, double* p1, double* p2) {
  product_rows<HalfPair>(SingleRows{S, N}, n, r0, r1, w1, w2, p1, p2);
}
#if defined(__x86_64__)
// The same rows with AVX2 (x86-64-v3: every x86 CPU since about 2013), chosen at run time.
__attribute__((target("arch=x86-64-v3"))) void product_rows_avx2(const double* G, std::size_t N, std::size_t n,
                                                                 std::size_t r0, std::size_t r1, const double* w1,
                                                                 const double* w2, double* p1, double* p2) {
  product_rows<Quad>(DoubleRows{G, N}, n, r0, r1, w1, w2, p1, p2);
}
// From the single-precision copy.
__attribute__((target("arch=x86-64-v3"))) void product_rows_single_avx2(const float* S, std::size_t N, std::size_t n,
                                                                        std::size_t r0, std::size_t r1,
                                                                        const double* w1, const double* w2, double* p1,
                                                                        double* p2) {
  product_rows<Quad>(SingleRows{S, N}, n, r0, r1, w1, w2, p1, p2);
}
// The same four-double code again for CPUs with AVX-512 (x86-64-v4), for its 32 vector registers
// (the quad's eight sums, eight weights and its entries fit without spilling): the same
// operations, so the same bits; faster on the single-precision copy, equal in double
// (docs/performance.md, "Four rows a pass").
__attribute__((target("arch=x86-64-v4"))) void product_rows_avx512(const double* G, std::size_t N, std::size_t n,
                                                                   std::size_t r0, std::size_t r1, const double* w1,
                                                                   const double* w2, double* p1, double* p2) {
  product_rows<Quad>(DoubleRows{G, N}, n, r0, r1, w1, w2, p1, p2);
}
__attribute__((target("arch=x86-64-v4"))) void product_rows_single_avx512(const float* S, std::size_t N, std::size_t n,
                                                                          std::size_t r0, std::size_t r1,
                                                                          const double* w1, const double* w2,
                                                                          double* p1, double* p2) {
  product_rows<Quad>(SingleRows{S, N}, n, r0, r1, w1, w2, p1, p2);
}
}  // namespace
ProductRows product_rows_for(KernelForm form) {
  return form == KernelForm::avx512 ? product_rows_avx512
         : form == KernelForm::avx2 ? product_rows_avx2
                                    : product_rows_portable;
}
SingleProductRows single_rows_for(KernelForm form) {
  return form == KernelForm::avx512 ? product_rows_single_avx512
         : form == KernelForm::avx2 ? product_rows_single_avx2
                                    : product_rows_single_portable;
}
#else
}  // namespace
ProductRows product_rows_for(KernelForm) { return product_rows_portable; }
SingleProductRows single_rows_for(KernelForm) { return product_rows_single_portable; }
#endif

namespace {

// Rows [r0, r1) of the stored triangle (rows N apart) take the removals, each entry all of them
// in order and in registers (one read and one write of the row, not one per removal; the same
// operations as one at a time, so the same bits), and, with a copy, go into S with the sums of
// their rounding errors' squares (own[r]: the diagonal's and the entries' right of it; and the
// column parts). The squares are summed in four lanes: any order is within the norms' rounding
// allowance. Vector:
// four doubles a step (AVX2 or AVX-512); else one entry at a time.
template <bool Vector>
[[gnu::always_inline]] inline void fold_rows(double* G, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1,
                                             Removals rm, CopySums& cs, double* own) {
  double w[kDeferredRemovals];  // fold() runs as the kDeferredRemovals-th is kept aside
  using V = Quad;
  V big = splat<V>(0.0);
  for (std::size_t r = r0; r < r1; ++r) {
    double* __restrict row = G + r * N;
    for (std::size_t k = 0; k < rm.K; ++k) w[k] = rm.u[k][r] / rm.d[k];
    const auto entry = [&](std::size_t c) {
      double v = row[c];
      for (std::size_t k = 0; k < rm.K; ++k) v -= w[k] * rm.u[k][c];
      row[c] = v;
      return v;
    };
    if (!cs.S) {
      std::size_t c = r;
      if constexpr (Vector)
        for (; c + 4 <= n; c += 4) {
          V v = load<V>(row + c);
          for (std::size_t k = 0; k < rm.K; ++k) v -= splat<V>(w[k]) * load<V>(rm.u[k] + c);
          store(row + c, v);
        }
      for (; c < n; ++c) entry(c);
      continue;
    }
    float* __restrict srow = cs.S + packed_row(r, N);  // srow[c]: column c (SingleRows)
    double* __restrict col = cs.col;
    const double g = entry(r);
    srow[r] = static_cast<float>(g);
    const double dg = g - static_cast<double>(srow[r]);  // the copy's rounding error, exact in double
    double tail = dg * dg, largest = std::abs(g);
    V sq = splat<V>(0.0);
    std::size_t c = r + 1;
    if constexpr (Vector)
      for (; c + 4 <= n; c += 4) {
        V v = load<V>(row + c);
        for (std::size_t k = 0; k < rm.K; ++k) v -= splat<V>(w[k]) * load<V>(rm.u[k] + c);
        store(row + c, v);
        const auto f = __builtin_convertvector(v, Single4);
        std::memcpy(srow + c, &f, sizeof f);
        const V d = v - __builtin_convertvector(f, V);
        const V d2 = d * d;
        sq += d2;
        store(col + c, load<V>(col + c) + d2);
        const V a = v < 0 ? -v : v;
        big = a > big ? a : big;
      }
    for (; c < n; ++c) {
      const double e = entry(c);
      srow[c] = static_cast<float>(e);
      const double d = e - static_cast<double>(srow[c]);
      tail += d * d;
      col[c] += d * d;
      largest = std::max(largest, std::abs(e));
    }
    own[r] = tail + sum(sq);
    cs.big = std::max(cs.big, largest);
  }
  cs.big = std::max({cs.big, big[0], big[1], big[2], big[3]});
}

void fold_rows_portable(double* G, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1, Removals rm,
                        CopySums& cs, double* own) {
  fold_rows<false>(G, N, n, r0, r1, rm, cs, own);
}
#if defined(__x86_64__)
__attribute__((target("arch=x86-64-v3"))) void fold_rows_avx2(double* G, std::size_t N, std::size_t n, std::size_t r0,
                                                              std::size_t r1, Removals rm, CopySums& cs, double* own) {
  fold_rows<true>(G, N, n, r0, r1, rm, cs, own);
}
// Again for AVX-512's 32 registers (sixteen removals' weights can stay in them; whole runs
// could not separate the two forms within this machine's noise): the same bits.
__attribute__((target("arch=x86-64-v4"))) void fold_rows_avx512(double* G, std::size_t N, std::size_t n, std::size_t r0,
                                                                std::size_t r1, Removals rm, CopySums& cs,
                                                                double* own) {
  fold_rows<true>(G, N, n, r0, r1, rm, cs, own);
}
}  // namespace
FoldRows fold_rows_for(KernelForm form) {
  return form == KernelForm::avx512 ? fold_rows_avx512 : form == KernelForm::avx2 ? fold_rows_avx2 : fold_rows_portable;
}
#else
}  // namespace
FoldRows fold_rows_for(KernelForm) { return fold_rows_portable; }
#endif

namespace {

// Rows [0, n) of a triangle times (w1, w2) into (y1, y2) over fixed row blocks (edges), each
// summing into its own partial vectors, added in block order: the same sums in the same order
// whatever the number of threads.
template <class T, class Kernel>
void blocked_product(Kernel rows, const T* base, std::size_t N, std::size_t n, const std::vector<std::size_t>& edge,
                     std::vector<double>& partial, const std::vector<double>& w1, const std::vector<double>& w2,
                     std::vector<double>& y1, std::vector<double>& y2, AdaptiveTeam& team) {
  const std::size_t B = edge.size() - 1;
  const AdaptiveTeam::Region region(team, static_cast<double>(n) * static_cast<double>(n));
  const int threads = region.threads();
  partial.resize(2 * B * n);  // block b writes (and zeroes) only its entries from edge[b] on
  double* P = partial.data();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (threads > 1)
  for (std::size_t b = 0; b < B; ++b) {
    double* p1 = P + 2 * b * n;
    double* p2 = p1 + n;
    std::fill(p1 + edge[b], p1 + n, 0.0);
    std::fill(p2 + edge[b], p2 + n, 0.0);
    rows(base, N, n, edge[b], edge[b + 1], w1.data(), w2.data(), p1, p2);
  }
  // Each entry's block sums in block order (in parallel too: a serial sweep of 2 B n adds took
  // 3 % of an N = 3,500 run on two threads, while the other thread waited).
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (std::size_t r = 0; r < n; ++r) {
    double s1 = 0, s2 = 0;
    for (std::size_t b = 0; b < B && edge[b] <= r; ++b) s1 += P[2 * b * n + r], s2 += P[(2 * b + 1) * n + r];
    y1[r] = s1;
    y2[r] = s2;
  }
}

}  // namespace

void triangle_product(ProductRows rows, const double* G, std::size_t N, std::size_t n,
                      const std::vector<std::size_t>& edge, std::vector<double>& partial, const std::vector<double>& w1,
                      const std::vector<double>& w2, std::vector<double>& y1, std::vector<double>& y2,
                      AdaptiveTeam& team) {
  blocked_product(rows, G, N, n, edge, partial, w1, w2, y1, y2, team);
}
void triangle_product(SingleProductRows rows, const float* S, std::size_t N, std::size_t n,
                      const std::vector<std::size_t>& edge, std::vector<double>& partial, const std::vector<double>& w1,
                      const std::vector<double>& w2, std::vector<double>& y1, std::vector<double>& y2,
                      AdaptiveTeam& team) {
  blocked_product(rows, S, N, n, edge, partial, w1, w2, y1, y2, team);
}

// ‖v − ref‖₂ over the first n entries.
double distance(const std::vector<double>& v, const std::vector<double>& ref, std::size_t n) {
  double s = 0;
  for (std::size_t r = 0; r < n; ++r) s += (v[r] - ref[r]) * (v[r] - ref[r]);
  return std::sqrt(s);
}

std::vector<ProductKernel> product_kernels() {
  std::vector<ProductKernel> forms;
  for (KernelForm f : kernel_forms_available())
    forms.push_back({kernel_form_name(f), product_rows_for(f), single_rows_for(f)});
  return forms;
}

}  // namespace asperity
