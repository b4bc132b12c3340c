#pragma once
// The junctions as the event method sees them (docs/model.md §4): the shared JunctionState plus the
// structures that make a force evaluation cheap. Slip thresholds are positions in X, kept in one
// min-heap; linear pinned junctions enter the force through two aggregate sums (Σk, Σk·x),
// slipping ones through one (Σ f); only never-slipped junctions (or, with area_law: always,
// every pinned one) need their own nonlinear force, given by the universal law instead of a
// bisection, packed for the inner loop (or binned for large N, binned_sum.hpp).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <queue>
#include <utility>
#include <vector>

#include "physics/universal_law.hpp"
#include "solve/core/junction_state.hpp"
#include "solve/core/problem.hpp"
#include "solve/event/binned_sum.hpp"

namespace asperity {

class EventJunctions {
 public:
  // Throws SolverError when the universal law's table cannot reach the needed accuracy.
  explicit EventJunctions(const Problem& problem);

  // Total junction force at slider position X [N].
  double force(double X) const {
    ++force_evals_;
    double F = K_p_ * X - S_p_ + F_sl_;
    if (binned_) return F + binned_->force(X);
    const std::size_t n = nl_w_.size();
    const double* w = nl_w_.data();
    const double* c = nl_c_.data();
    const double* x = nl_x_.data();
    if (n == 0) return F;
    const UniversalForceLaw& g = *table_;
    double Fnl = 0;
#pragma omp parallel for reduction(+ : Fnl) schedule(static) if (n > 65536)
    for (std::size_t j = 0; j < n; ++j) {
      const double d = X - x[j];
      Fnl += w[j] * d * g.g(c[j] * d);
    }
    return F + Fnl;
  }
  // Total area at slider position X [m²].
  double area(double X) const;

  bool has_threshold() const { return !heap_.empty(); }
  double next_threshold() const { return heap_.top().first; }  // m, the next slip position
  // Independent junctions slip only as X grows (their force is k·(X − x) or its Eq. (3) form).
  bool has_threshold_below() const { return false; }
  double next_threshold_below() const { return -HUGE_VAL; }
  std::int64_t n_slipping() const { return static_cast<std::int64_t>(slipping_.size()); }
  std::int64_t n_intact() const { return n_intact_; }
  std::int64_t force_evals() const { return force_evals_; }
  std::int64_t slips() const { return slips_; }
  std::int64_t repins() const { return repins_; }

  // Every pinned junction whose threshold X has reached slips; returns how many.
  std::int64_t slip_crossed(double X);
  // All slipping junctions repin at X, with no force jump.
  void repin_all(double X);

 private:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  // Above this many junctions the never-slipped ones are summed in bins (binned_sum.hpp):
  // O(bins) per force instead of O(N). Below it the exact sum is as fast, and exact.
  static constexpr std::size_t kBinnedMin = 20000;

  void nl_insert(std::size_t i, double anchor);
  void nl_remove(std::size_t i);
  void lin_insert(std::size_t i, double anchor);
  void start_slip(std::uint32_t i);
  void maybe_resum();

  const ContactLaw& law_;
  // The law this method applies: with α_b = 0, Eq. (3) leaves every area at A0 and both area
  // laws are the same linear model, treated as until_first_slip.
  AreaLaw area_law_;
  bool nonlinear_;
  JunctionState J_;
  // Per-junction constants: w = ℓ0 E [N/m], c = ψ per metre of displacement [1/m], the slip
  // displacement of a never-slipped junction [m]; under area_law: always, the slipping force
  // and its contact.
  std::vector<double> w_, c_, d_s_, f_sl_;
  std::vector<JunctionContact> contact_sl_;
  std::vector<std::size_t> nl_pos_;
  // Nonlinear (never-slipped, or pinned under area_law: always) junctions, packed.
  std::vector<std::uint32_t> nl_idx_;
  std::vector<double> nl_w_, nl_c_, nl_x_, nl_A0_;
  std::shared_ptr<const UniversalForceLaw> table_;  // process-wide (universal_force_law)
  std::optional<BinnedUniversalSum> binned_;        // large N under until_first_slip
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap_;
  std::vector<std::uint32_t> slipping_;
  double K_p_ = 0, S_p_ = 0, F_sl_ = 0, A_fixed_ = 0;
  std::int64_t n_intact_ = 0, slips_ = 0, repins_ = 0, updates_ = 0;
  mutable std::int64_t force_evals_ = 0;
};

}  // namespace asperity
