#pragma once
// Quasi-static tangential contact on the contact map of a normal solve (surface/normal_contact.hpp):
// the elastomer half-space (E, ν) touches a rigid slider over the pixels where the normal solve
// found pressure, and the slider moves by δ along x (x = j·pixel, along a row of the map). Each
// pixel in contact sticks (its surface displacement u_x equals δ) until its shear traction q
// reaches its bound, then slips (|q| at the bound, u_x lagging δ). Boundary elements on an FFT:
// Cerruti's x-x kernel integrated exactly over each pixel's uniform traction
// (cerruti_pixel_compliance), on the grid zero-padded to 2n × 2n like the normal solve (an isolated
// contact, not periodic).
//
// ν = 0.5 only: the half-space couples normal and tangential tractions through the coefficient
// (1 − 2ν)/(4πG) (Johnson, Contact Mechanics, eq. 3.19–3.20), which vanishes for an incompressible
// body such as the paper's PDMS. Then shear leaves the normal solve's pressures and contact area
// unchanged and the tangential problem is solved on them alone; for other ν it would not be, and
// the constructor refuses them. The traction is along x only (q_y = 0), as in Cattaneo's and
// Mindlin's solutions, whose stick condition u_x = δ it satisfies exactly.
//
// Under monotonic loading from δ = 0 with no pixel's slip reversing, the state at δ does not
// depend on the path: it is the minimiser of ½ qᵀKq − δ Σ q over the tractions |q| ≤ bound (the
// Karush–Kuhn–Tucker conditions are the stick and slip conditions), found by the bound-constrained
// conjugate gradient of surface/bounded_cg.hpp. tangential_curve checks that no pixel's slip
// reverses between its points.
#include <cstddef>
#include <memory>
#include <vector>

#include "surface/normal_contact.hpp"

namespace asperity {

struct TangentialContactSettings {
  double E_Pa = 0;            // Young's modulus of the elastomer (the slider is rigid)
  double nu = 0.5;            // Poisson's ratio: 0.5 only (see above)
  double tolerance = 1e-10;   // on max |u_x − δ| over the sticking pixels, relative to δ
  int max_iterations = 5000;  // per solve
  int threads = 1;            // the result's bits do not depend on it
};

// The traction bound [Pa] of each pixel of a normal solve's contact map (0 outside the contact):
// a constant shear strength σ (the junction models' σ per unit area), or Coulomb's μ p.
std::vector<double> shear_strength_bound(const NormalContact& contact, double shear_strength_Pa);
std::vector<double> coulomb_bound(const NormalContact& contact, double friction_coefficient);

// The x-displacement [m] at offset (x, y) from the centre of a pixel of half-sides a × b carrying a
// uniform unit x-traction [Pa]: Cerruti's kernel (1 + ν)/(πE) · [(1 − ν)/r + ν x²/r³] integrated
// over the pixel in closed form.
double cerruti_pixel_compliance(double x_m, double y_m, double a_m, double b_m, double E_Pa, double nu);

struct TangentialState {
  double displacement_m = 0;  // δ
  double force_N = 0;         // Q = Σ q A
  std::size_t contact_pixels = 0;
  std::size_t slipping_pixels = 0;  // |q| at its bound
  int iterations = 0;
  int convolutions = 0;
  double residual = 0;  // max |u_x − δ| over the free pixels / δ at the end
  bool converged = false;
};

class TangentialContact {
 public:
  // bound_Pa: n × n traction bounds (> 0 in contact, 0 outside), e.g. coulomb_bound(normal, μ).
  // Throws std::invalid_argument on ν ≠ 0.5, a non-positive modulus, a bound that is negative or not
  // finite, or a map of the wrong size.
  TangentialContact(std::size_t n, double pixel_m, std::vector<double> bound_Pa, const TangentialContactSettings& s);
  ~TangentialContact();
  TangentialContact(const TangentialContact&) = delete;
  TangentialContact& operator=(const TangentialContact&) = delete;

  // The state at slider displacement δ ≥ 0, starting from the last state scaled to δ (call with
  // increasing δ along a loading path).
  TangentialState solve(double displacement_m);
  // dQ/dδ of the last state: the stiffness of its sticking pixels with the slipping ones held at
  // their bounds (one more solve, unbounded, on the stick zone).
  double tangent_stiffness_N_per_m();
  // dQ/dδ at δ → 0, every pixel in contact sticking.
  double initial_stiffness_N_per_m();
  // Full sliding: every pixel at its bound, Q = Σ bound A, reached at δ = max over the contact of
  // u_x under those tractions.
  double full_sliding_force_N() const;
  double full_sliding_displacement_m();

  std::size_t n() const { return n_; }
  double pixel_m() const { return pixel_m_; }
  const std::vector<double>& traction_Pa() const { return q_; }  // of the last solve
  // Of the last solve, per pixel: 0 outside the contact, 1 sticking, 2 slipping.
  std::vector<unsigned char> slip_map() const;

 private:
  struct Operator;
  void iterate(double delta, const std::vector<unsigned char>& free, bool bounded, std::vector<double>& q,
               TangentialState& st);
  double sticking_stiffness(const std::vector<unsigned char>& sticking);

  std::size_t n_;
  double pixel_m_;
  std::vector<double> bound_;
  TangentialContactSettings settings_;
  std::unique_ptr<Operator> op_;
  std::vector<double> q_;
  double last_delta_ = 0;
};

struct TangentialCurvePoint {
  double displacement_m = 0;
  double force_N = 0;
  double tangent_stiffness_N_per_m = 0;  // NaN when not asked for
  double slip_area_fraction = 0;         // slipping pixels / contact pixels
  int iterations = 0;
  bool converged = false;
};

struct TangentialCurve {
  std::vector<TangentialCurvePoint> points;
  double initial_stiffness_N_per_m = 0;
  double full_sliding_force_N = 0;
  double full_sliding_displacement_m = 0;
  bool monotone = true;                               // no pixel's slip reversed (slip → stick) between two points
  std::vector<std::vector<unsigned char>> slip_maps;  // per point (slip_map()), when asked
};

// Q(δ) along the increasing displacements given (each ≥ 0), from the contact's state at δ = 0.
TangentialCurve tangential_curve(TangentialContact& contact, const std::vector<double>& displacements_m,
                                 bool tangent_stiffness = true, bool keep_slip_maps = false);

}  // namespace asperity
