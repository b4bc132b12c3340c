#pragma once
// The junction models' interface force against the slider's displacement X, quasi-statically, with
// the shear-induced area reduction off (α_b = 0: each junction keeps its area and its Mindlin
// stiffness k_i = 8Ga_i/(2 − ν), docs/model.md §1) and slipping junctions keeping their force (ε = 1):
// junction i sticks (its displacement Σ_j C_ij f_j equals X) until f_i reaches σ A_i, then slips at
// f_i = σ A_i. Independent junctions (C diagonal, C_ii = 1/k_i) give F(X) = Σ min(k_i X, σ A_i);
// interacting ones (docs/model.md §8) add Cerruti's kernel averaged over the discs (uniform or rigid
// weighting) off the diagonal, and the state at X is the minimiser of ½ fᵀCf − X Σ f over
// |f_i| ≤ σ A_i (surface/bounded_cg.hpp), path-independent under monotonic loading as long as no
// junction stops slipping. The reference the continuum comparison (studies/continuum_comparison.hpp)
// sets beside the tangential contact on the same contact map.
#include <cstddef>
#include <vector>

#include "physics/elastic_interaction.hpp"

namespace asperity {

struct QuasiStaticJunctions {
  std::vector<double> area_m2, x_m, y_m;  // discs of these areas at these centres (disjoint if interacting)
  double E_Pa = 0;
  double nu = 0.5;
  double shear_strength_Pa = 0;  // σ: junction i slips at σ A_i
  bool interacting = false;
  TractionWeighting weighting = TractionWeighting::rigid;
  double tolerance = 1e-10;     // of the bounded CG (relative to X)
  int max_iterations = 100000;  // of the bounded CG per displacement; a point that
                                // reaches it is marked not converged
};

struct JunctionCurvePoint {
  double displacement_m = 0;
  double force_N = 0;
  double slip_area_fraction = 0;  // area of the slipping junctions / their total area
  bool converged = false;
};

struct JunctionCurve {
  std::vector<JunctionCurvePoint> points;
  double initial_stiffness_N_per_m = 0;    // dF/dX at X → 0
  double full_sliding_force_N = 0;         // Σ σ A_i
  double full_sliding_displacement_m = 0;  // the X from which every junction slips
  bool monotone = true;                    // no junction stopped slipping between two points
};

// Largest population the interacting form takes (its dense N × N compliance: 3.2 GB at 20,000).
inline constexpr std::size_t kMaxQuasiStaticJunctions = 20000;

// F(X) at the increasing displacements given. Throws std::invalid_argument on overlapping discs
// (interacting), a non-positive area, modulus or strength, or more than kMaxQuasiStaticJunctions
// interacting junctions.
JunctionCurve quasi_static_junction_curve(const QuasiStaticJunctions& j, const std::vector<double>& displacements_m);

}  // namespace asperity
