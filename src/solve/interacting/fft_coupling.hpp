#pragma once
// y = C x for the junctions' elastic coupling C (solve/interacting/interaction_matrix.hpp: the
// disc-averaged Cerruti kernel, zero diagonal) without the N × N matrix: a precorrected FFT
// (Phillips & White 1997, IEEE TCAD 16(10)). Issue 26's building block for a matrix-free solve.
//
// Why it is exact in the far field up to interpolation: the pair average over discs i and j is
// S_i S_j K, with K Cerruti's point kernel and S_a = Σ_m s_m(a) ∇^2m the disc-averaging operator
// (s_m = a^2m μ_m / (4^m m!²), μ_m the traction's radial moment: 1/(m+1) uniform,
// 2^m m!/(2m+1)!! rigid; physics/elastic_interaction.hpp). Each junction's force is spread on a
// p × p patch of a regular grid with the weights S_a L(x) of the tensor Lagrange basis L of order
// p (and read back with the same weights, so the product stays symmetric), the grid convolves
// with K in O(G log G) (FFTW), and this is accurate to O((h/d)^p) for pairs d apart on a grid of
// spacing h. Pairs closer than `near_cells` · h are corrected to their exact C_ij (a sparse,
// symmetric table built once), so the error is set by near_cells and the order: the knobs.
// Cost per product: N p² scatter and gather, two FFTs of the padded grid, the near table.
// Memory: O(N · near pairs per junction + grid), not N².
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "physics/elastic_interaction.hpp"

namespace asperity {

struct Problem;

// The defaults (order 8, half the mean spacing, 12 cells: 6 spacings) keep max_i |ỹ_i − y_i| /
// max_i |y_i| at 1–4e-9 on `bench interacting`'s populations, N = 1,200 to 20,000
// (results/bench/fft_coupling.csv).
struct FftCouplingSettings {
  int order = 8;                  // Lagrange points per direction (even, 2 … 12)
  double near_cells = 12.0;       // pairs closer than this many grid cells are exact
  double cell_per_spacing = 0.5;  // grid spacing / mean junction spacing (√(box area / N))
};

class FftCoupling {
 public:
  // Junction centres and disc radii [m], the elastomer (E [Pa], ν), the traction weighting.
  FftCoupling(const std::vector<double>& x_m, const std::vector<double>& y_m, const std::vector<double>& radius_m,
              double E_pa, double nu, TractionWeighting weighting, FftCouplingSettings settings = {});
  // The problem's junctions (its initial areas' discs; the full kernel: a cut-off is refused).
  explicit FftCoupling(const Problem& problem, FftCouplingSettings settings = {});
  ~FftCoupling();
  FftCoupling(const FftCoupling&) = delete;
  FftCoupling& operator=(const FftCoupling&) = delete;

  std::size_t size() const { return n_; }
  // y = C x, both size() entries [N → m]. Uses the object's FFT buffers: one product at a time.
  void apply(const double* x, double* y) const;

  std::size_t near_pairs() const { return (col_.size() - n_) / 2; }  // exact pairs i < j
  std::size_t grid_points() const { return M_ * M_; }                // the padded grid
  double cell_m() const { return h_; }

 private:
  struct Fft;
  using NearRows = std::vector<std::vector<std::pair<std::uint32_t, double>>>;  // row i: (j > i, value)
  // The constructor's steps: each junction's patch and weights on the grid, the grid's kernel
  // and its spectrum, the near pairs' corrections, and their table.
  void place_patches(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& radius,
                     TractionWeighting weighting, double ox, double oy);
  std::vector<double> grid_kernel(double E, double nu);
  double grid_pair(const std::vector<double>& kernel, std::size_t i, std::size_t j) const;
  void correct_near_pairs(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& radius,
                          double E, double nu, TractionWeighting weighting, double near_cells, double extent,
                          const std::vector<double>& kernel);
  void store_near_table(const NearRows& upper, const std::vector<double>& self);
  std::size_t n_ = 0, M_ = 0;
  int p_ = 0;
  double h_ = 0;
  std::vector<int> bx_, by_;      // each junction's patch: grid nodes bx … bx + p − 1 (and y)
  std::vector<double> w_;         // its p × p weights, junction-major
  std::vector<std::size_t> row_;  // near table (CSR, both triangles and the diagonal)
  std::vector<std::uint32_t> col_;
  std::vector<double> val_;  // exact C_ij minus the grid's own value of the pair
  std::unique_ptr<Fft> fft_;
};

}  // namespace asperity
