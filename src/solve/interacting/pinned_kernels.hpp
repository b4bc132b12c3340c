#pragma once
// The pinned operator's SIMD kernels (PinnedCompliance's passes over its stored triangle): the
// products of a triangle with two vectors, in double or from the single-precision copy, and the
// fold of removals kept aside into it. Each has a portable form and AVX2 / AVX-512 clones chosen
// at run time (kernel_form.hpp); pinned_kernels.cpp is built without fused multiply-add
// (CMakeLists.txt), so every form groups and rounds every sum alike and gives the same bits.
// Internal to the interacting solver (and its tests and probes).
#include <cstddef>
#include <vector>

#include "solve/core/adaptive_team.hpp"
#include "solve/interacting/kernel_form.hpp"

namespace asperity {

// The single-precision copy's layout: row r packed from its diagonal, its entry at column c at
// S[packed_row(r, N) + c] (row r holds N − r entries).
inline std::size_t packed_row(std::size_t r, std::size_t N) { return r * N - r * (r + 1) / 2; }

// Rows [r0, r1) of an upper triangle (row r's entry at column c ≥ r at G[r·N + c], or packed in
// single precision) times (w1, w2): row r's sums added into p[r], its entries' transposed
// products into p[c > r].
using ProductRows = void (*)(const double* G, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1,
                             const double* w1, const double* w2, double* p1, double* p2);
using SingleProductRows = void (*)(const float* S, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1,
                                   const double* w1, const double* w2, double* p1, double* p2);
ProductRows product_rows_for(KernelForm form);
SingleProductRows single_rows_for(KernelForm form);

// One form of the chord pass's product kernel. The forms this CPU can run
// (kernel_forms_available()) are listed for tests: every form groups every sum alike, so all
// give the same bits. A PinnedCompliance uses the form kernel_form() names (ASPERITY_KERNEL).
struct ProductKernel {
  const char* name;
  ProductRows rows;
  SingleProductRows single_rows;
};
std::vector<ProductKernel> product_kernels();

// Removals kept aside (as G − Σ u uᵀ/d) before they are folded into the stored triangle in one
// pass: each fold reads and writes G once instead of once per removal, and every product pays
// O(n) per removal kept aside. Sixteen from n = kSingleFrom on (or the size the constructor is
// given for the copy: tests lower it), where the triangle outgrows the cache and a fold is bound
// by memory traffic (one fold at n = 5,000 in a microbenchmark: 2.9 ms a removal at eight, 2.4 at
// sixteen; whole runs could not separate the two within this machine's noise); eight below, where
// a fold is cheap and sixteen measured no faster (N = 1,200, three rounds). A fold takes at most
// this many.
inline constexpr std::size_t kDeferredRemovals = 16;

// The removals kept aside, as a fold applies them: entry (r, s) of the triangle takes
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
// Rows [r0, r1) of the stored triangle (rows N apart) take the removals (at most
// kDeferredRemovals) and, with a copy (cs.S), go into S with the sums of their rounding errors'
// squares (own[r]: the diagonal's and the entries' right of it; cs.col: the column parts).
using FoldRows = void (*)(double* G, std::size_t N, std::size_t n, std::size_t r0, std::size_t r1, Removals rm,
                          CopySums& cs, double* own);
FoldRows fold_rows_for(KernelForm form);

// Rows [0, n) of a triangle times (w1, w2) into (y1, y2) over fixed row blocks (edge: B + 1
// edges), each block summing into its own part of `partial` (a workspace), the parts added in
// block order: the same bits on any number of threads (team chooses how many).
void triangle_product(ProductRows rows, const double* G, std::size_t N, std::size_t n,
                      const std::vector<std::size_t>& edge, std::vector<double>& partial, const std::vector<double>& w1,
                      const std::vector<double>& w2, std::vector<double>& y1, std::vector<double>& y2,
                      AdaptiveTeam& team);
void triangle_product(SingleProductRows rows, const float* S, std::size_t N, std::size_t n,
                      const std::vector<std::size_t>& edge, std::vector<double>& partial, const std::vector<double>& w1,
                      const std::vector<double>& w2, std::vector<double>& y1, std::vector<double>& y2,
                      AdaptiveTeam& team);

// ‖v − ref‖₂ over the first n entries.
double distance(const std::vector<double>& v, const std::vector<double>& ref, std::size_t n);

}  // namespace asperity
