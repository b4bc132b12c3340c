#include "solve/interacting/fft_coupling.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "physics/contact_law.hpp"
#include "solve/core/problem.hpp"
#include "surface/fft_planner.hpp"
#include "surface/neighbour_grid.hpp"

namespace asperity {

namespace {

// Grid points per side at most (before padding): a population far wider than it is dense gets a
// coarser grid (and more exact pairs) rather than an unbounded one (2 × 1,024 padded: 32 MB).
constexpr std::size_t kMaxGridSide = 1024;
// Exact pairs at most (8 bytes of value and 4 of column each, twice): a population whose
// junctions sit in a few tight clusters far apart would need nearly all N² pairs here.
constexpr std::size_t kMaxNearPairs = 100'000'000;

// The smallest size ≥ n whose factors are 2, 3, 5 and 7 (FFTW's fast sizes).
std::size_t fft_size(std::size_t n) {
  for (std::size_t m = std::max<std::size_t>(n, 1);; ++m) {
    std::size_t r = m;
    for (std::size_t f : {2, 3, 5, 7})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

// Coefficients (ascending powers) of the Lagrange basis polynomials on the nodes 0 … p − 1.
std::vector<std::vector<double>> lagrange_basis(int p) {
  std::vector<std::vector<double>> basis(p);
  for (int a = 0; a < p; ++a) {
    std::vector<double> c{1.0};
    for (int k = 0; k < p; ++k) {
      if (k == a) continue;
      std::vector<double> next(c.size() + 1, 0.0);  // c · (u − k) / (a − k)
      for (std::size_t e = 0; e < c.size(); ++e) {
        next[e + 1] += c[e] / (a - k);
        next[e] -= c[e] * k / (a - k);
      }
      c = std::move(next);
    }
    basis[a] = std::move(c);
  }
  return basis;
}

// The q-th derivative at u of the polynomial with ascending coefficients c.
double derivative(const std::vector<double>& c, int q, double u) {
  double sum = 0;
  for (int k = static_cast<int>(c.size()) - 1; k >= q; --k) {
    double falling = 1;  // k! / (k − q)!
    for (int t = 0; t < q; ++t) falling *= k - t;
    sum = sum * u + c[k] * falling;
  }
  return sum;
}

// s_m(a) / a^2m of the disc-averaging operator S_a = Σ_m s_m ∇^2m (see the header).
double smoothing_coefficient(int m, TractionWeighting w) {
  double fact = 1;
  for (int k = 1; k <= m; ++k) fact *= k;
  return traction_radial_moment(m, w) / (std::pow(4.0, m) * fact * fact);
}

}  // namespace

struct FftCoupling::Fft {
  explicit Fft(std::size_t M) : grid(M), kernel_spectrum(M * (M / 2 + 1)) {}
  FftBuffers grid;
  std::vector<std::complex<double>> kernel_spectrum;  // K̂ / M² (the inverse's normalisation)
};

FftCoupling::FftCoupling(const Problem& problem, FftCouplingSettings settings)
    : FftCoupling(
          problem.x, problem.y,
          [&] {
            // (Checked before anything is built.)
            if (problem.interaction_cutoff > 0)
              throw std::invalid_argument(
                  "FftCoupling: a cut-off kernel is not translation invariant (the full kernel only)");
            std::vector<double> r(problem.size());
            for (std::size_t i = 0; i < r.size(); ++i) r[i] = disc_radius(problem.A0[i]);
            return r;
          }(),
          problem.law.E, problem.law.nu, problem.interaction_weighting, settings) {}

FftCoupling::~FftCoupling() = default;

FftCoupling::FftCoupling(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& radius,
                         double E, double nu, TractionWeighting weighting, FftCouplingSettings s)
    : n_(x.size()), p_(s.order) {
  if (y.size() != n_ || radius.size() != n_) throw std::invalid_argument("FftCoupling: x, y and radius differ in size");
  if (p_ < 2 || p_ > 12 || p_ % 2 != 0) throw std::invalid_argument("FftCoupling: the order must be even, 2 to 12");
  if (!(s.near_cells >= 1.0 && s.near_cells <= 64.0) || !(s.cell_per_spacing > 0 && s.cell_per_spacing <= 100))
    throw std::invalid_argument("FftCoupling: near_cells must lie in [1, 64] and cell_per_spacing in (0, 100]");
  if (n_ == 0) return;
  const auto [xmin, xmax] = std::minmax_element(x.begin(), x.end());
  const auto [ymin, ymax] = std::minmax_element(y.begin(), y.end());
  const double wx = *xmax - *xmin, wy = *ymax - *ymin, wide = std::max(wx, wy);
  // The grid: h from the mean spacing, coarsened so that the padded grid stays bounded.
  const double spacing = wx * wy > 0 ? std::sqrt(wx * wy / n_) : wide / n_;
  h_ = std::max(s.cell_per_spacing * spacing, wide / (kMaxGridSide - p_ - 2));
  if (!(h_ > 0) || !std::isfinite(h_)) h_ = 1.0;  // one junction, or all at one point: the near table does it all
  const int half = p_ / 2;
  const double ox = *xmin - half * h_, oy = *ymin - half * h_;
  const std::size_t side = static_cast<std::size_t>(wide / h_) + p_ + 2;
  M_ = fft_size(2 * side - 1);
  place_patches(x, y, radius, weighting, ox, oy);
  const std::vector<double> kernel = grid_kernel(E, nu);
  const double extent = std::max({std::abs(*xmin), std::abs(*xmax), std::abs(*ymin), std::abs(*ymax)});
  correct_near_pairs(x, y, radius, E, nu, weighting, s.near_cells, extent, kernel);
}

// Each junction's patch and weights S_a L: Σ_m s_m a^2m Σ_k C(m, k) ∂x^2k L_a ∂y^2(m−k) L_b.
void FftCoupling::place_patches(const std::vector<double>& x, const std::vector<double>& y,
                                const std::vector<double>& radius, TractionWeighting weighting, double ox, double oy) {
  const int half = p_ / 2;
  const auto basis = lagrange_basis(p_);
  const int m_max = (p_ - 1) / 2;  // ∇^2m of a polynomial of degree p − 1
  std::vector<double> coefficient(m_max + 1);
  for (int m = 0; m <= m_max; ++m) coefficient[m] = smoothing_coefficient(m, weighting);
  const std::size_t pp = static_cast<std::size_t>(p_) * p_;
  bx_.resize(n_), by_.resize(n_), w_.assign(n_ * pp, 0.0);
  std::vector<double> lx((m_max + 1) * p_), ly((m_max + 1) * p_), inverse_h2q(m_max + 1);
  for (int q = 0; q <= m_max; ++q) inverse_h2q[q] = std::pow(h_, -2.0 * q);  // the 2q-th derivative's unit
  for (std::size_t j = 0; j < n_; ++j) {
    const double tx = (x[j] - ox) / h_, ty = (y[j] - oy) / h_;
    bx_[j] = static_cast<int>(std::floor(tx)) - (half - 1);
    by_[j] = static_cast<int>(std::floor(ty)) - (half - 1);
    for (int q = 0; q <= m_max; ++q)
      for (int a = 0; a < p_; ++a) {
        const double scale = inverse_h2q[q];
        lx[q * p_ + a] = derivative(basis[a], 2 * q, tx - bx_[j]) * scale;
        ly[q * p_ + a] = derivative(basis[a], 2 * q, ty - by_[j]) * scale;
      }
    double* w = w_.data() + j * pp;
    double a2m = 1;
    for (int m = 0; m <= m_max; ++m, a2m *= radius[j] * radius[j]) {
      double binomial = 1;
      for (int k = 0; k <= m; ++k) {
        const double c = coefficient[m] * a2m * binomial;
        for (int a = 0; a < p_; ++a)
          for (int b = 0; b < p_; ++b) w[a * p_ + b] += c * lx[k * p_ + a] * ly[(m - k) * p_ + b];
        binomial = binomial * (m - k) / (k + 1);
      }
    }
  }
}

// The point kernel on the grid's offsets (circular: offset −d at M − d; none aliases since M ≥
// 2 side − 1), 0 at zero offset (every pair that sees it is in the near table); its spectrum goes
// to the FFT buffers.
std::vector<double> FftCoupling::grid_kernel(double E, double nu) {
  const std::size_t M = M_;
  std::vector<double> kernel(M * M);
  for (std::size_t i = 0; i < M; ++i)
    for (std::size_t j = 0; j < M; ++j) {
      const double di = i <= M / 2 ? double(i) : double(i) - double(M),
                   dj = j <= M / 2 ? double(j) : double(j) - double(M);
      kernel[i * M + j] = (i == 0 && j == 0) ? 0.0 : cerruti_compliance(di * h_, dj * h_, E, nu);
    }
  fft_ = std::make_unique<Fft>(M);
  std::copy(kernel.begin(), kernel.end(), fft_->grid.real());
  fft_->grid.forward();
  const std::size_t nc = M * (M / 2 + 1);
  const double norm = 1.0 / (double(M) * double(M));
  for (std::size_t k = 0; k < nc; ++k)
    fft_->kernel_spectrum[k] = std::complex<double>(fft_->grid.spectrum()[k][0], fft_->grid.spectrum()[k][1]) * norm;
  return kernel;
}

// The grid's own value of a pair: Σ w_i[a][b] w_j[c][d] K(offset of the nodes).
double FftCoupling::grid_pair(const std::vector<double>& kernel, std::size_t i, std::size_t j) const {
  const std::size_t M = M_, pp = static_cast<std::size_t>(p_) * p_;
  const double *wi = w_.data() + i * pp, *wj = w_.data() + j * pp;
  const long ex = bx_[i] - bx_[j], ey = by_[i] - by_[j];
  double sum = 0;
  for (int a = 0; a < p_; ++a)
    for (int c = 0; c < p_; ++c) {
      const long e = ex + a - c;
      const double* krow = kernel.data() + static_cast<std::size_t>(e >= 0 ? e : e + long(M)) * M;
      for (int b = 0; b < p_; ++b) {
        double inner = 0;
        for (int d = 0; d < p_; ++d) {
          const long f = ey + b - d;
          inner += wj[c * p_ + d] * krow[f >= 0 ? f : f + long(M)];
        }
        sum += wi[a * p_ + b] * inner;
      }
    }
  return sum;
}

// Near pairs by a cell list of cell size R = near_cells · h. The grid's error of a pair d apart is
// about Σ_m (a/d)^2m (h/d)^(p − 2m) (the m-th smoothing term comes from the 2m-th derivative of
// the interpolant); a disc wider than a cell keeps it at (h/R)^p out to R · a/h. Each near pair's
// exact compliance minus the grid's own value goes to the near table.
void FftCoupling::correct_near_pairs(const std::vector<double>& x, const std::vector<double>& y,
                                     const std::vector<double>& radius, double E, double nu,
                                     TractionWeighting weighting, double near_cells, double extent,
                                     const std::vector<double>& kernel) {
  const double R = near_cells * h_;
  const auto reach = [&](std::size_t i) { return R * std::max(1.0, radius[i] / h_); };
  const double widest = *std::max_element(radius.begin(), radius.end());
  const auto rings = static_cast<std::int64_t>(std::ceil(std::max(1.0, widest / h_)));
  NeighbourGrid grid(R, extent);
  for (std::size_t j = 0; j < n_; ++j) grid.insert(j, x[j], y[j]);
  // Every j > i within the reach of i or j, in the cells around i.
  const auto for_near = [&](std::size_t i, auto&& visit) {
    grid.for_each_near(x[i], y[i], rings, [&](std::size_t j) {
      const double dx = x[i] - x[j], dy = y[i] - y[j];
      if (j > i && std::hypot(dx, dy) < std::max(reach(i), reach(j))) visit(j, dx, dy);
      return true;
    });
  };
  // Counted first: a table too large is refused before it is built.
  std::size_t pairs = 0;
#pragma omp parallel for reduction(+ : pairs) schedule(dynamic, 64)
  for (std::size_t i = 0; i < n_; ++i) for_near(i, [&](std::size_t, double, double) { ++pairs; });
  if (pairs > kMaxNearPairs)
    throw std::runtime_error("FftCoupling: " + std::to_string(pairs) +
                             " exact pairs (the junctions are too clustered for the grid)");
  NearRows upper(n_);  // j > i
  std::vector<double> self(n_);
  std::atomic<bool> overlap{false};  // no exception may leave the parallel loop
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < n_; ++i) {
    self[i] = -grid_pair(kernel, i, i);
    for_near(i, [&](std::size_t j, double dx, double dy) {
      if (!(std::hypot(dx, dy) >= radius[i] + radius[j]) || !(radius[i] >= 0) || !(radius[j] >= 0)) {
        overlap = true;
        return;
      }
      const double exact = disc_compliance(dx, dy, radius[i], radius[j], E, nu, weighting);
      upper[i].emplace_back(static_cast<std::uint32_t>(j), exact - grid_pair(kernel, i, j));
    });
    std::sort(upper[i].begin(), upper[i].end());
  }
  if (overlap) throw std::invalid_argument("FftCoupling: two junctions' discs overlap, or a radius is invalid");
  store_near_table(upper, self);
}

// Both triangles and the diagonal, rows in column order.
void FftCoupling::store_near_table(const NearRows& upper, const std::vector<double>& self) {
  row_.assign(n_ + 1, 0);
  for (std::size_t i = 0; i < n_; ++i) {
    row_[i + 1] += upper[i].size() + 1;
    for (const auto& [j, v] : upper[i]) ++row_[j + 1];
  }
  for (std::size_t i = 0; i < n_; ++i) row_[i + 1] += row_[i];
  col_.resize(row_[n_]), val_.resize(row_[n_]);
  std::vector<std::size_t> next(row_.begin(), row_.end() - 1);
  for (std::size_t i = 0; i < n_; ++i) {  // lower entries of row j come from rows i < j, in order
    col_[next[i]] = static_cast<std::uint32_t>(i), val_[next[i]++] = self[i];
    for (const auto& [j, v] : upper[i]) col_[next[j]] = static_cast<std::uint32_t>(i), val_[next[j]++] = v;
    for (const auto& [j, v] : upper[i]) col_[next[i]] = j, val_[next[i]++] = v;
  }
}
void FftCoupling::apply(const double* x, double* y) const {
  if (n_ == 0) return;
  const std::size_t M = M_, pp = static_cast<std::size_t>(p_) * p_;
  double* grid = fft_->grid.real();
  std::fill(grid, grid + M * M, 0.0);
  for (std::size_t j = 0; j < n_; ++j) {
    const double* w = w_.data() + j * pp;
    for (int a = 0; a < p_; ++a) {
      double* g = grid + static_cast<std::size_t>(bx_[j] + a) * M + by_[j];
      for (int b = 0; b < p_; ++b) g[b] += x[j] * w[a * p_ + b];
    }
  }
  fft_->grid.forward();
  auto* spec = reinterpret_cast<std::complex<double>*>(fft_->grid.spectrum());
  const std::size_t nc = M * (M / 2 + 1);
  for (std::size_t k = 0; k < nc; ++k) spec[k] *= fft_->kernel_spectrum[k];
  fft_->grid.inverse();
  for (std::size_t i = 0; i < n_; ++i) {
    const double* w = w_.data() + i * pp;
    double sum = 0;
    for (int a = 0; a < p_; ++a) {
      const double* g = grid + static_cast<std::size_t>(bx_[i] + a) * M + by_[i];
      for (int b = 0; b < p_; ++b) sum += w[a * p_ + b] * g[b];
    }
    for (std::size_t k = row_[i]; k < row_[i + 1]; ++k) sum += val_[k] * x[col_[k]];
    y[i] = sum;
  }
}

}  // namespace asperity
