#pragma once
// The pinned set P of an interacting population and the linear algebra the fast solver keeps for
// it (docs/model.md §8). With D a diagonal reference compliance (u_i' at some force: exact for linear
// junctions, a choice of the iteration for Eq. (3) ones) and h_i = x_i + Σ_{j slipping} C_ij f_j,
// M = D + C_PP is kept as its explicit inverse G = M⁻¹, with a0 = G 1 and b0 = −G h, so that
// the pinned forces are f = X a0 + b0 − G Δ(f) (Δ = 0 for linear junctions).
// A slip removes one position (rank-one: kept aside as G − g gᵀ/g_qq, O(N) a product, and
// folded into the stored triangle 8 or 16 at a time, one O(N²) pass for all of them, each entry
// taking them in registers); a repin adds the slipping junctions back and a change of D takes
// effect, both by a rebuild (LAPACK Cholesky inverse in place, O(N³)); after about N rank-one
// updates G is rebuilt too (their rounding accumulates). G is symmetric: only its
// upper triangle is kept up to date and read (half the memory traffic of every pass and update),
// and C, symmetric with a zero diagonal, lives in the strict lower triangle of the same buffer
// (LAPACK's Cholesky and inverse never touch it). Memory: N² doubles for C and G, plus N²/2 floats
// for the single-precision copy below.
// Positions q = 0 .. size()−1 index P; junction(q) is the junction there.
// From N = kSingleFrom on, a single-precision copy S of the stored triangle (half the bytes of a
// pass, 2 N² more bytes of memory) serves the passes whose error it provably keeps within a
// budget: a pass reads S and adds c = (T − S) w_ref, kept from the last exact pass at w_ref, so
// its error is (T − S)(w − w_ref), at most ‖T_i − S_i‖₂ ‖w − w_ref‖₂ on row i (the rounding
// errors' norm, bounded as the copy is written). Otherwise the pass is exact and becomes the new
// reference.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solve/core/adaptive_team.hpp"
#include "solve/core/problem.hpp"
#include "solve/interacting/huge_page_allocator.hpp"
#include "solve/interacting/interaction_matrix.hpp"
#include "solve/interacting/kernel_form.hpp"

namespace asperity {

class PinnedCompliance {
 public:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  // The single-precision copy is kept from this many junctions on: there the stored triangle
  // (16 MB) outgrows half of a typical last-level cache and a pass is bound by memory traffic.
  static constexpr std::size_t kSingleFrom = 2048;

  // Every junction pinned at position q = i, with reference compliance reference[i] [m/N],
  // nonlinear (Eq. 3) or not, h = 0; G built. single_from: N from which the single-precision
  // copy is kept, and n from which sixteen removals wait for a fold instead of eight (tests lower
  // it).
  PinnedCompliance(const Problem& problem, std::vector<double> reference, bool nonlinear,
                   std::size_t single_from = kSingleFrom);

  std::size_t size() const { return n_; }  // |P|
  std::size_t junction(std::size_t q) const { return idx_[q]; }
  std::size_t position(std::size_t i) const { return pos_[i]; }  // npos: slipping
  bool nonlinear(std::size_t q) const { return nl_[q] != 0; }
  std::size_t n_nonlinear() const { return n_nl_; }
  double reference(std::size_t q) const { return D_[q]; }  // m/N
  double a0(std::size_t q) const { return a0_[q]; }        // df_q/dX of the linear system [N/m]
  double b0(std::size_t q) const { return b0_[q]; }        // N
  double coupling(std::size_t i, std::size_t j) const {    // C_ij [m/N], junctions
    return i == j ? 0.0 : G_[std::max(i, j) * N_ + std::min(i, j)];
  }

  // y1 = G w1, y2 = G w2 over P with w1, w2 (size() entries) zero outside the positions
  // `columns` (one pass over the stored triangle of G). y1, y2 are overwritten.
  void apply(const std::vector<std::size_t>& columns, const std::vector<double>& w1, const std::vector<double>& w2,
             std::vector<double>& y1, std::vector<double>& y2);
  // The errors a pass may make on y1 (by position, absolute) and on y2 (absolute, every entry)
  // by reading the single-precision copy.
  struct PassBudget {
    std::vector<double> y1;
    double y2 = 0;
  };
  enum class Pass { exact, single, refresh };  // refresh: exact, and the copy's new reference
  // The same product, from the single-precision copy when its error bound is within `budget`
  // on every entry (a product over the whole triangle only, and with the copy kept).
  Pass apply(const std::vector<std::size_t>& columns, const std::vector<double>& w1, const std::vector<double>& w2,
             std::vector<double>& y1, std::vector<double>& y2, const PassBudget& budget);
  bool single_kept() const { return !single_.S.empty(); }
  std::int64_t single_passes() const { return single_.passes; }
  std::int64_t single_refreshes() const { return single_.refreshes; }
  // G's row q (= column q), size() entries.
  std::vector<double> row(std::size_t q) const;

  // A new reference compliance at position q [m/N]; takes effect at the next rebuild().
  void set_reference(std::size_t q, double D) { D_[q] = D; }
  void rebuild();  // G, a0, b0 from scratch for the current P, D and h

  // The junction at position q leaves P and carries the constant force f_slip [N] from now on:
  // G loses its row and column (rank-one), a0, b0 and h follow in closed form; the last position
  // moves into q.
  void remove(std::size_t q, double f_slip);
  // Slipping junction i joins P (not nonlinear unless asked); returns its position. G, a0, b0
  // are stale until set_anchors() and rebuild().
  std::size_t add(std::size_t i, bool nonlinear);
  // h_q = anchor[junction(q)]: every junction pinned, nobody slips.
  void set_anchors(const std::vector<double>& anchor_m);

  // Wall time by phase [s], for benchmarks: passes over G (exact, on the copy, the removals kept
  // aside), folds of the removals into G, rebuilds (LAPACK), and the rest of each removal.
  struct Timing {
    double exact_s = 0, single_s = 0, deferred_s = 0, fold_s = 0, rebuild_s = 0, remove_s = 0;
  };
  Timing timing() const {
    return {teams_.product.seconds(),
            teams_.single.seconds(),
            teams_.deferred.seconds(),
            teams_.fold.seconds(),
            rebuild_s_,
            remove_s_};
  }
  std::int64_t rank_one_updates() const { return rank_one_; }
  std::int64_t rebuilds() const { return rebuilds_; }

 private:
  std::size_t N_ = 0, n_ = 0;
  std::size_t large_from_ = kSingleFrom;  // the constructor's single_from: removals wait 16 at a time from there
  KernelForm form_;                       // the SIMD kernels' form (kernel_form.hpp), chosen at construction
  // The threads of each kind of parallel pass, chosen by measuring them (adaptive_team.hpp): a
  // loaded machine never makes a pass slower than one thread. Work: entries of the triangle
  // (removals kept aside × positions for the deferred correction); the thresholds are where two
  // threads start to pay on a quiet machine.
  // Work below which a loop over G stays on one thread (thread start-up costs more).
  static constexpr double kParallelWork = 200000;
  struct Teams {
    explicit Teams(int threads)
        : product(threads, 2.0 * kParallelWork),
          single(threads, 2.0 * kParallelWork),
          fold(threads, 2.0 * kParallelWork),
          deferred(threads, kParallelWork / 4.0) {}
    AdaptiveTeam product, single, fold, deferred;
  };
  Teams teams_;
  // y1 = G w1, y2 = G w2 over all of P (w1, w2: size() entries).
  void symmetric_product(const std::vector<double>& w1, const std::vector<double>& w2, std::vector<double>& y1,
                         std::vector<double>& y2);
  // y −= Σ u (uᵀ w)/d over the removals not yet folded.
  void subtract_deferred(const std::vector<double>& w1, const std::vector<double>& w2, std::vector<double>& y1,
                         std::vector<double>& y2);
  // The fixed row blocks of a product over the triangle (n + 1 edges).
  std::vector<std::size_t> row_blocks() const;

  // N × N, row-major. Upper triangle (column ≥ row): G over positions of P, leading n × n block
  // (G is symmetric: every pass over it reads half as much). Strict lower triangle: C over
  // junctions, C_ij at [max(i, j) · N + min(i, j)].
  std::vector<double, HugePageAllocator<double>> G_;
  // Removals not yet applied to the stored triangle: G = triangle − Σ u uᵀ/d, in order (u over
  // the current positions). fold() applies them in one pass over the triangle.
  struct Deferred {
    std::vector<double> u;
    double d;
  };
  std::vector<Deferred> deferred_;
  void fold();
  // One pass over the triangle's rows: the removals kept aside folded in (when asked), and the
  // single-precision copy with its row norms written (when kept).
  void write_rows(bool removals);
  std::vector<double> partial_;  // the symmetric product's per-block sums (a workspace)
  // The single-precision copy (empty: not kept): S packed by rows (row r from its diagonal,
  // N − r entries), the rows' 2-norm bounds of the triangle T it copies, and the reference of
  // the last exact pass.
  struct Single {
    std::vector<float, HugePageAllocator<float>> S;
    std::vector<double> row_error, c1, c2, ref1, ref2, last1,
        last2;           // row_error: ‖T_r − S_r‖₂; last: the last pass's w
    bool valid = false;  // c, ref hold for the current triangle
    bool has_last = false;
    bool usable = false;  // S and row_error hold for the current triangle (and no entry overflowed)
    std::int64_t passes = 0, refreshes = 0;
  };
  Single single_;
  // Rows [0, n) of T written into S, with their norms (after a rebuild or fold).
  void copy_single();
  // Row norms and usability from a copy's per-row and per-block sums.
  void finish_single(const std::vector<std::size_t>& edge, const std::vector<double>& own,
                     const std::vector<double>& biggest);
  std::vector<std::uint32_t> idx_;  // position → junction
  std::vector<std::size_t> pos_;    // junction → position (npos: slipping)
  std::vector<double> D_, h_, a0_, b0_;
  std::vector<std::uint8_t> nl_;
  std::size_t n_nl_ = 0;
  std::int64_t updates_since_rebuild_ = 0, rank_one_ = 0, rebuilds_ = 0;
  double rebuild_s_ = 0, remove_s_ = 0;  // LAPACK in rebuilds; removals outside their folds
};

}  // namespace asperity
