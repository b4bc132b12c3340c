#pragma once
// Force and area of many never-slipped junctions in O(bins) instead of O(N).
//
// Under area_law: until_first_slip every never-slipped junction is anchored at X = 0, so its
// force is w_j X g(c_j X) and its area A0_j (1 − φ_j²), φ = ψ g(ψ), ψ = c_j X (universal law).
// Junctions are grouped in bins of relative width `rel_width` in c; inside a bin the sums are a
// Taylor series of order 3 around the bin centre c̄ (ψ̄ = c̄ X, u_j = (c_j − c̄) X):
//     Σ_j w_j g(c_j X) = Σ_n g⁽ⁿ⁾(ψ̄) Xⁿ/n! · Σ_j w_j (c_j − c̄)ⁿ,
// with the moments Σ_j w_j (c_j − c̄)ⁿ kept up to date as junctions leave. The error is the
// 4th-order remainder, |g⁗| (ψ δ/2)⁴ / 24 relative, for δ = rel_width: the caller picks δ
// from its tolerance. A junction leaving costs O(1); so does a bin whose centre falls beyond
// the table (it is summed exactly over its members).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "physics/universal_law.hpp"

namespace asperity {

// Bin width δ (relative, in c) for a relative error of the sums well below `tol` when
// ψ ≤ psi_max: the Taylor remainder |g⁗|(ψ δ/2)⁴/24 is small for the universal law (its error
// in docs/solvers.md, measured by tests/unit/solve/test_binned_sum.cpp), capped at 20 %.
inline double binned_rel_width(double tol, double psi_max) {
  const double d = 10.0 * std::pow(tol, 0.25) / (psi_max > 1.0 ? psi_max : 1.0);
  return d < 0.2 ? d : 0.2;
}

class BinnedUniversalSum {
 public:
  // w [N/m] (ℓ0 E), c [1/m] (ψ per metre of displacement), A0 [m²], one entry per junction,
  // all initially present. `law` must outlive this object.
  BinnedUniversalSum(const UniversalForceLaw& law, const std::vector<double>& w, const std::vector<double>& c,
                     const std::vector<double>& A0, double rel_width);

  void remove(std::size_t i);    // junction i (index into the constructor's arrays) leaves
  double force(double X) const;  // N, Σ_j w_j X g(c_j X) over present junctions
  double area(double X) const;   // m², Σ_j A0_j (1 − φ_j²)
  std::size_t size() const { return present_; }
  std::size_t bins() const { return bins_.size(); }

 private:
  struct Bin {
    double c_mid = 0;                  // 1/m, expansion centre
    double mw[4] = {};                 // Σ w (c − c̄)ⁿ, n = 0..3
    double ma[4] = {};                 // Σ A0 (c − c̄)ⁿ
    std::uint32_t begin = 0, end = 0;  // members in the sorted arrays
    std::uint32_t count = 0;
  };
  double exact_force(const Bin& b, double X) const;
  double exact_area(const Bin& b, double X) const;

  const UniversalForceLaw& law_;
  std::vector<Bin> bins_;
  // Members sorted by bin, for removal and the exact fallback.
  std::vector<double> w_, c_, A0_;
  std::vector<std::uint8_t> present_flag_;
  std::vector<std::uint32_t> slot_of_;  // junction → position in the sorted arrays
  std::vector<std::uint32_t> bin_of_;   // sorted position → bin
  std::size_t present_ = 0;
};

}  // namespace asperity
