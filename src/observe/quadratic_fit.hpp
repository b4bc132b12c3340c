#pragma once
// Shape of the area-vs-force curve A(Q) on the loading branch (docs/model.md §5):
//  - the paper's quadratic fit A = A0 − α Q² with A0 fixed (least squares in α only);
//  - a quasi-linearity index: the best exponent n of A0 − A = c Qⁿ (n ≈ 1 quasi-linear,
//    n ≈ 2 quadratic), fitted by least squares in log space.
// Both work on model samples and on measured curves (any pair of equally long Q, A spans).
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "solve/core/observer.hpp"

namespace asperity {

struct MeasuredCurve;  // scene/scene.hpp

struct QuadraticFit {
  double alpha = std::numeric_limits<double>::quiet_NaN();  // m²/N², A ≈ A0 − α Q²
  double R2 = std::numeric_limits<double>::quiet_NaN();     // 1 − SS_res/SS_tot of A
  std::size_t n_points = 0;                                 // points used
};

struct ShapeIndex {
  double n = std::numeric_limits<double>::quiet_NaN();       // exponent of A0 − A = c Qⁿ
  double c = std::numeric_limits<double>::quiet_NaN();       // prefactor [m²/Nⁿ]
  double R2_log = std::numeric_limits<double>::quiet_NaN();  // R² of the fit in log space
  std::size_t n_points = 0;                                  // points used
};

// Least squares of A = A0 − α Q² with A0 fixed. Non-finite points are skipped. alpha is NaN
// when no point has Q ≠ 0; R2 is NaN when SS_tot = 0 (fewer than two distinct areas).
QuadraticFit fit_quadratic_area(std::span<const double> Q, std::span<const double> A, double A0);
QuadraticFit fit_quadratic_area(const std::vector<Sample>& loading, double A0);
// A measured curve; A0 is the caller's choice (the paper: the initial area at Q = 0).
QuadraticFit fit_quadratic_area(const MeasuredCurve& curve, double A0);

// Least squares of log(A0 − A) = log c + n log Q over the points with Q > q_min_fraction·Q_max
// (Q_max: largest Q of the input) and A0 − A > 0. NaN fields when fewer than two such points
// with distinct Q exist.
ShapeIndex fit_power_law(std::span<const double> Q, std::span<const double> A, double A0, double q_min_fraction = 0.05);
ShapeIndex fit_power_law(const std::vector<Sample>& loading, double A0, double q_min_fraction = 0.05);
ShapeIndex fit_power_law(const MeasuredCurve& curve, double A0, double q_min_fraction = 0.05);

}  // namespace asperity
