#include "solve/interacting/pinned_compliance.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
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

// Row blocks of the symmetric product: fixed, so its sums do not depend on the thread count.
constexpr std::size_t kProductBlocks = 16;
// Below n / kFewColumns weighted columns, the product reads those columns alone (strided above
// the diagonal, about 8 times the cost of a sequential read: break-even near n / 9).
constexpr std::size_t kFewColumns = 10;
// Pinned sets below this size are factorised and inverted by LAPACK on one thread.
constexpr std::size_t kParallelLapack = 2000;
// Removals kept aside (as G − Σ u uᵀ/d) before they are folded into the stored triangle in one
// pass: each fold reads and writes G once instead of once per removal, and every product pays
// O(n) per removal kept aside. Sixteen from n = kSingleFrom on (or the size the constructor is
// given for the copy: tests lower it), where the triangle outgrows the cache and a fold is bound
// by memory traffic (one fold at n = 5,000 in a microbenchmark: 2.9 ms a removal at eight, 2.4 at
// sixteen; whole runs could not separate the two within this machine's noise); eight below, where
// a fold is cheap and sixteen measured no faster (N = 1,200, three rounds).
constexpr std::size_t kDeferredRemovals = 16;
constexpr std::size_t kDeferredRemovalsSmall = 8;

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

// The stored triangle's entries as four doubles: read as they are, or widened from single
// precision (the copy; exact, so every form reads the same values).
template <class V> inline V entries(const double* p) { return load<V>(p); }
using Single4 = float __attribute__((vector_size(16)));
template <class V> inline V entries(const float* p);
template <> inline Quad entries<Quad>(const float* p) {
  Single4 s;
  std::memcpy(&s, p, sizeof s);
  return __builtin_convertvector(s, Quad);
}
template <> inline HalfPair entries<HalfPair>(const float* p) {
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

// Rows [r0, r1) of the stored triangle times (w1, w2): row r's own sums into p[r], its entries'
// transposed products into p[c > r]. Four rows at a time, then a pair and an odd row: each load
// of w and each update of p serves four rows of G (the loop is bound by loads and stores, not
// arithmetic; a throw-away microbenchmark, one thread, AVX2: 1.16x the two-row form at n = 1,200
// in double, 1.2-1.4x at 3,500-5,000 on the single-precision copy). Every sum has one fixed order
// (four lanes, combined pairwise; a row's entries left of the lanes, the quad's diagonal block,
// first): the same bits from every form (AVX-512, AVX2, 16-byte vectors), on any number of
// threads. Each
// p[c] takes its rows' terms in row order, as a row-by-row loop would.
template <class V, class Rows>
[[gnu::always_inline]] inline void product_rows(Rows rows, std::size_t n, std::size_t r0, std::size_t r1,
                                                const double* __restrict w1, const double* __restrict w2,
                                                double* __restrict p1, double* __restrict p2) {
  std::size_t r = r0;
  for (; r + 3 < r1; r += 4) {
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
  // Two or three rows left: a pair, then an odd row.
  if (r + 1 < r1) {
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
    r += 2;
  }
  if (r < r1) {  // an odd row left: alone, the same way
    const auto* __restrict A = rows(r);
    const double gd = A[r];
    one_row<V>(A, r, r + 1, n, gd * w1[r], gd * w2[r], w1, w2, p1, p2);
  }
}

using ProductRows = void (*)(const double*, std::size_t, std::size_t, std::size_t, std::size_t, const double*,
                             const double*, double*, double*);
using SingleProductRows = void (*)(const float*, std::size_t, std::size_t, std::size_t, std::size_t, const double*,
                                   const double*, double*, double*);
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
                                                                          const double* w1, const double* w2,
                                                                          double* p1, double* p2) {
  product_rows<Quad>(SingleRows{S, N}, n, r0, r1, w1, w2, p1, p2);
}
// The same four-double code again for CPUs with AVX-512 (x86-64-v4), for its 32 vector registers
// (the quad's eight sums, eight weights and its entries fit without spilling): the same
// operations, so the same bits. Microbenchmark, one thread: 1.16-1.6x the AVX2 form on the
// single-precision copy at n = 2,400-5,000, equal in double.
__attribute__((target("arch=x86-64-v4"))) void product_rows_avx512(const double* G, std::size_t N, std::size_t n,
                                                                     std::size_t r0, std::size_t r1, const double* w1,
                                                                     const double* w2, double* p1, double* p2) {
  product_rows<Quad>(DoubleRows{G, N}, n, r0, r1, w1, w2, p1, p2);
}
__attribute__((target("arch=x86-64-v4"))) void product_rows_single_avx512(const float* S, std::size_t N,
                                                                            std::size_t n, std::size_t r0,
                                                                            std::size_t r1, const double* w1,
                                                                            const double* w2, double* p1, double* p2) {
  product_rows<Quad>(SingleRows{S, N}, n, r0, r1, w1, w2, p1, p2);
}
ProductRows product_rows_for(KernelForm form) {
  return form == KernelForm::avx512 ? product_rows_avx512 : form == KernelForm::avx2 ? product_rows_avx2 : product_rows_portable;
}
SingleProductRows single_rows_for(KernelForm form) {
  return form == KernelForm::avx512 ? product_rows_single_avx512
         : form == KernelForm::avx2 ? product_rows_single_avx2
                                    : product_rows_single_portable;
}
#else
ProductRows product_rows_for(KernelForm) { return product_rows_portable; }
SingleProductRows single_rows_for(KernelForm) { return product_rows_single_portable; }
#endif

// The removals kept aside, as fold() applies them: entry (r, s) of the triangle takes
// −(u[r]/d) u[s] of each in order.
struct Removals {
  const double* const* u;  // K vectors over the positions
  const double* d;         // their pivots
  std::size_t K;
};
// What a pass writing the single-precision copy adds up, per row block: the column parts of the
// rows' squared rounding errors (col[c]) and the largest |entry|.
struct CopySums {
  float* S = nullptr;  // the packed copy (null: not written)
  double* col = nullptr;
  double big = 0;
};

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

using FoldRows = void (*)(double*, std::size_t, std::size_t, std::size_t, std::size_t, Removals, CopySums&, double*);
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
__attribute__((target("arch=x86-64-v4"))) void fold_rows_avx512(double* G, std::size_t N, std::size_t n,
                                                                  std::size_t r0, std::size_t r1, Removals rm,
                                                                  CopySums& cs, double* own) {
  fold_rows<true>(G, N, n, r0, r1, rm, cs, own);
}
FoldRows fold_rows_for(KernelForm form) {
  return form == KernelForm::avx512 ? fold_rows_avx512 : form == KernelForm::avx2 ? fold_rows_avx2 : fold_rows_portable;
}
#else
FoldRows fold_rows_for(KernelForm) { return fold_rows_portable; }
#endif

// Rows [0, n) of a triangle times (w1, w2) into (y1, y2) over fixed row blocks (edges), each
// summing into its own partial vectors, added in block order: the same sums in the same order
// whatever the number of threads.
template <class T, class Kernel>
void triangle_product(Kernel rows, const T* base, std::size_t N, std::size_t n, const std::vector<std::size_t>& edge,
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

// ‖v − ref‖₂ over the first n entries.
double distance(const std::vector<double>& v, const std::vector<double>& ref, std::size_t n) {
  double s = 0;
  for (std::size_t r = 0; r < n; ++r) s += (v[r] - ref[r]) * (v[r] - ref[r]);
  return std::sqrt(s);
}

}  // namespace

std::vector<ProductKernel> product_kernels() {
  std::vector<ProductKernel> forms;
  for (KernelForm f : kernel_forms_available())
    forms.push_back({kernel_form_name(f), product_rows_for(f), single_rows_for(f)});
  return forms;
}

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
    while (r < n && static_cast<double>(r) * static_cast<double>(n) - 0.5 * static_cast<double>(r) * (static_cast<double>(r) - 1.0) < want) ++r;
    edge[b] = r;
  }
  return edge;
}

void PinnedCompliance::symmetric_product(const std::vector<double>& w1, const std::vector<double>& w2,
                                         std::vector<double>& y1, std::vector<double>& y2) const {
  const ProductRows rows = product_rows_for(form_);
  triangle_product(rows, G_.data(), N_, n_, row_blocks(), partial_, w1, w2, y1, y2, teams_.product);
  subtract_deferred(w1, w2, y1, y2);
}

void PinnedCompliance::subtract_deferred(const std::vector<double>& w1, const std::vector<double>& w2,
                                         std::vector<double>& y1, std::vector<double>& y2) const {
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
                                               std::vector<double>& y2, const PassBudget& budget) const {
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
