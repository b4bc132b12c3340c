#pragma once
// Frictionless elastic normal contact of a rough surface (HeightMap) with a rigid flat under a
// normal load: the boundary-element method on an FFT, isolated or periodic. Surface displacements are the Boussinesq
// response to pressures uniform over each pixel (Love's closed form for a rectangle, Johnson,
// Contact Mechanics, eq. 3.25), convolved by FFT (FFTW) on a grid padded to 2n × 2n, so the
// contact is not periodic (a sphere on a flat). The pressures come from the constrained conjugate
// gradient of Polonsky & Keer (Wear 231, 1999) at a prescribed total load.
#include <cstddef>
#include <vector>

#include "surface/height_map.hpp"

namespace asperity {

struct NormalContactSettings {
  double E_star_Pa = 0;  // contact modulus E / (1 − ν²) of the elastic body (the flat is rigid)
  // false: an isolated contact (a sphere), the grid zero-padded to 2n × 2n, pixel kernel of Love;
  // true: the map repeats periodically (a nominally flat rough surface), the spectral kernel
  // u(q) = 2 p(q) / (E* |q|) with the mean displacement left free (Stanley & Kato 1997).
  bool periodic = false;
  double load_N = 0;         // total normal load
  double tolerance = 1e-10;  // on Σ|Δp|A / P between two iterations
  int max_iterations = 5000;
  // Threads of the FFTs and of the loops over pixels (the solve's own blocked workers; FFTW's threads
  // for the periodic kernel's transforms). The work is cut in fixed blocks and the sums are taken in
  // a fixed order, so the result does not depend on the number of threads (see the tests).
  int threads = 1;
  // Isolated contacts on grids of ≥ 128 pixels (n even) start from the solution on the grid of
  // half the width, interpolated (coarse-to-fine), instead of a uniform pressure: the same answer
  // to the tolerance in fewer iterations.
  bool coarse_start = true;
};

struct NormalContact {
  std::vector<double> pressure_Pa;  // per pixel, ≥ 0; n × n like the map
  std::vector<double> gap_m;        // per pixel, ≥ 0 (0 in contact, to the solver's tolerance)
  double area_m2 = 0;               // pixels in contact × pixel area
  double approach_m = 0;            // rigid-body approach of the flat past the highest summit
  int iterations = 0;               // on this grid
  int coarse_iterations = 0;        // on the coarser grids of the coarse-to-fine start, all of them
  int convolutions = 0;             // kernel convolutions (one FFT pair each) on this grid
  double residual = 0;              // the last Σ|Δp|A / P
  bool converged = false;
};

// Throws std::invalid_argument on a load, modulus or map that cannot be solved (non-positive,
// empty, not finite).
NormalContact solve_normal_contact(const HeightMap& map, const NormalContactSettings& settings);

// Surface displacement [m] at offset (x, y) from the centre of a pixel of sides a × b loaded by a
// uniform unit pressure, times E*: Love's rectangle (Johnson eq. 3.25) / π.
double love_rectangle(double x, double y, double a, double b);

}  // namespace asperity
