#include "solve/quasi_static/junction_curve.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "physics/contact_law.hpp"
#include "surface/bounded_cg.hpp"

namespace asperity {
namespace {

void check(const QuasiStaticJunctions& j) {
  const std::size_t n = j.area_m2.size();
  if (n == 0 || j.x_m.size() != n || j.y_m.size() != n)
    throw std::invalid_argument("quasi-static junctions: areas and positions of at least one junction are needed");
  if (!(j.E_Pa > 0) || !std::isfinite(j.E_Pa) || !(j.shear_strength_Pa > 0) || !std::isfinite(j.shear_strength_Pa))
    throw std::invalid_argument("quasi-static junctions: E and sigma must be positive and finite");
  for (const double a : j.area_m2)
    if (!(a > 0) || !std::isfinite(a)) throw std::invalid_argument("quasi-static junctions: an area is not positive");
  if (!(j.tolerance > 0) || j.max_iterations < 1)
    throw std::invalid_argument("quasi-static junctions: the tolerance and max_iterations must be positive");
  if (j.interacting && n > kMaxQuasiStaticJunctions)
    throw std::invalid_argument("quasi-static junctions: more than " + std::to_string(kMaxQuasiStaticJunctions) +
                                " interacting junctions (a dense compliance matrix)");
}

// C: 1/k_i on the diagonal, the disc-averaged Cerruti kernel off it when interacting.
Eigen::MatrixXd compliance(const QuasiStaticJunctions& j) {
  const std::size_t n = j.area_m2.size();
  const auto N = static_cast<Eigen::Index>(n);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(N, N);
  for (std::size_t i = 0; i < n; ++i) {
    const auto I = static_cast<Eigen::Index>(i);
    C(I, I) = 1 / circle_stiffness(initial_diameter(j.area_m2[i]), j.E_Pa, j.nu);
    if (!j.interacting) continue;
    for (std::size_t k = 0; k < i; ++k) {
      const double dx = j.x_m[i] - j.x_m[k], dy = j.y_m[i] - j.y_m[k];
      const double c = disc_compliance(dx, dy, disc_radius(j.area_m2[i]), disc_radius(j.area_m2[k]), j.E_Pa, j.nu,
                                       j.weighting);  // throws on overlapping discs
      C(I, static_cast<Eigen::Index>(k)) = C(static_cast<Eigen::Index>(k), I) = c;
    }
  }
  return C;
}

}  // namespace

JunctionCurve quasi_static_junction_curve(const QuasiStaticJunctions& j, const std::vector<double>& displacements_m) {
  check(j);
  const std::size_t n = j.area_m2.size();
  const Eigen::MatrixXd C = compliance(j);
  auto apply = [&](const std::vector<double>& in, std::vector<double>& out) {
    Eigen::Map<Eigen::VectorXd>(out.data(), C.rows()).noalias() =
        C.selfadjointView<Eigen::Lower>() * Eigen::Map<const Eigen::VectorXd>(in.data(), C.rows());
  };
  pixel_loops::Workers W(1);
  BoundedCgSettings cs;
  cs.tolerance = j.tolerance;
  cs.max_iterations = j.max_iterations;
  std::vector<double> bound(n);
  double total_area = 0;
  for (std::size_t i = 0; i < n; ++i) bound[i] = j.shear_strength_Pa * j.area_m2[i], total_area += j.area_m2[i];
  const std::vector<unsigned char> all(n, 1);
  auto sum = [](const std::vector<double>& v) {
    double s = 0;
    for (const double x : v) s += x;
    return s;
  };

  JunctionCurve out;
  {
    std::vector<double> f(n, 0.0);  // C f = 1: the stiffness of all sticking
    bounded_cg(apply, 1.0, all, nullptr, f, cs, W);
    out.initial_stiffness_N_per_m = sum(f);
  }
  out.full_sliding_force_N = sum(bound);
  {
    std::vector<double> u(n);
    apply(bound, u);
    out.full_sliding_displacement_m = *std::max_element(u.begin(), u.end());
  }
  std::vector<double> f(n, 0.0);
  std::vector<unsigned char> slipping(n, 0);
  double last = 0;
  for (const double X : displacements_m) {
    if (!(X >= last) || !std::isfinite(X))
      throw std::invalid_argument("quasi-static junctions: the displacements must increase from 0");
    JunctionCurvePoint p;
    p.displacement_m = X;
    const double scale = last > 0 ? X / last : 0.0;  // the last state scaled, clipped
    for (std::size_t i = 0; i < n; ++i) f[i] = std::clamp(f[i] * scale, -bound[i], bound[i]);
    last = X;
    p.converged = X == 0 || bounded_cg(apply, X, all, &bound, f, cs, W).converged;
    double slip_area = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const bool s = X > 0 && std::abs(f[i]) >= bound[i];
      if (slipping[i] && !s) out.monotone = false;
      slipping[i] = s;
      slip_area += s ? j.area_m2[i] : 0.0;
    }
    p.force_N = sum(f);
    p.slip_area_fraction = slip_area / total_area;
    out.points.push_back(p);
  }
  return out;
}

}  // namespace asperity
