#include "surface/normal_contact.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <new>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "surface/fft_convolution.hpp"
#include "surface/pixel_loops.hpp"

namespace asperity {
using pixel_loops::block_sums;
using pixel_loops::for_each_pixel;
using pixel_loops::kParallelFrom;
using pixel_loops::Workers;

double love_rectangle(double x, double y, double a, double b) {
  // a, b: half-sides. Johnson (1985) eq. 3.25 with E* = E/(1 − ν²): u = F / (π E*).
  auto term = [](double s, double t1, double t2) {  // s · ln((t1 + √(t1² + s²)) / (t2 + √(t2² + s²)))
    if (s == 0) return 0.0;
    return s * std::log((t1 + std::hypot(t1, s)) / (t2 + std::hypot(t2, s)));
  };
  const double F =
      term(x + a, y + b, y - b) + term(y + b, x + a, x - a) + term(x - a, y - b, y + b) + term(y - b, x - a, x + a);
  return F / std::numbers::pi;
}

namespace {

// Grids at least this wide start from the solution on the grid of half their width (below it the
// coarse solve would not pay for itself).
constexpr std::size_t kCoarseStartFrom = 128;
// The coarse solve needs only to locate the contact and the shape of the pressures: its own
// discretisation differs from the fine one by far more than this.
constexpr double kCoarseTolerance = 1e-6;

// The map averaged over 2 × 2 pixels (n even).
HeightMap halve(const HeightMap& m) {
  HeightMap c;
  c.n = m.n / 2;
  c.pixel_m = 2 * m.pixel_m;
  c.h_m.resize(c.n * c.n);
  for (std::size_t i = 0; i < c.n; ++i)
    for (std::size_t j = 0; j < c.n; ++j) {
      const double* r0 = &m.h_m[2 * i * m.n + 2 * j];
      const double* r1 = r0 + m.n;
      c.h_m[i * c.n + j] = 0.25 * ((r0[0] + r0[1]) + (r1[0] + r1[1]));
    }
  return c;
}

// Pressures on the n/2 grid carried to the n grid, bilinear between pixel centres (a fine pixel's
// centre lies a quarter of a coarse pixel from the nearest coarse centre), held at the edges.
std::vector<double> refine(const std::vector<double>& pc, std::size_t n) {
  const std::size_t m = n / 2;
  auto at = [&](long i, long j) {
    i = std::clamp(i, 0L, static_cast<long>(m) - 1), j = std::clamp(j, 0L, static_cast<long>(m) - 1);
    return pc[static_cast<std::size_t>(i) * m + static_cast<std::size_t>(j)];
  };
  std::vector<double> p(n * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const long I = static_cast<long>(i / 2), J = static_cast<long>(j / 2);
      const long I2 = i % 2 ? I + 1 : I - 1, J2 = j % 2 ? J + 1 : J - 1;  // the other neighbour
      p[i * n + j] = 0.5625 * at(I, J) + 0.1875 * (at(I2, J) + at(I, J2)) + 0.0625 * at(I2, J2);
    }
  return p;
}

void check_inputs(const HeightMap& map, const NormalContactSettings& s) {
  const std::size_t n = map.n;
  if (n < 2 || map.h_m.size() != n * n || !(map.pixel_m > 0) || !std::isfinite(map.pixel_m))
    throw std::invalid_argument("normal contact: an n x n height map with n >= 2 and a positive pixel size is needed");
  if (!(s.E_star_Pa > 0) || !std::isfinite(s.E_star_Pa) || !(s.load_N > 0) || !std::isfinite(s.load_N))
    throw std::invalid_argument("normal contact: E* and the load must be positive and finite");
  for (const double h : map.h_m)
    if (!std::isfinite(h)) throw std::invalid_argument("normal contact: a height is not finite");
}

// Start: the pressures of the same contact on the grid of half the width (coarse-to-fine: the
// contact set and the pressures' shape come at a quarter of the cost per iteration), else uniform.
void start_pressures(const HeightMap& map, const NormalContactSettings& s, NormalContact& out) {
  const std::size_t n = map.n, nn = n * n;
  const double A = map.pixel_m * map.pixel_m;
  std::vector<double>& p = out.pressure_Pa;
  if (!s.periodic && s.coarse_start && n % 2 == 0 && n >= kCoarseStartFrom) {
    NormalContactSettings cs = s;
    cs.tolerance = std::max(s.tolerance, kCoarseTolerance);
    const NormalContact coarse = solve_normal_contact(halve(map), cs);
    out.coarse_iterations = coarse.iterations + coarse.coarse_iterations;
    p = refine(coarse.pressure_Pa, n);
    double total = 0;
    for (const double x : p) total += x;
    total *= A;
    if (total > 0) {
      for (double& x : p) x *= s.load_N / total;
      return;
    }
  }
  p.assign(nn, s.load_N / (A * static_cast<double>(nn)));
}

// The convolution u = K p of the map's kind; for an isolated map also the kernel's values at the
// offsets (influence), which the direct correction reads.
std::unique_ptr<Convolution> make_convolution(const HeightMap& map, const NormalContactSettings& s, Workers& W,
                                              std::vector<double>& influence) {
  const std::size_t n = map.n;
  if (s.periodic) {
    // u(q) = 2 p(q) / (E* |q|); the mean (q = 0) displacement is the free approach.
    const double qL = 2 * std::numbers::pi / map.length_m();
    return std::make_unique<PeriodicConvolution>(n, W, [&](long ky, long kx) {
      const double q = qL * std::hypot(static_cast<double>(ky), static_cast<double>(kx));
      return q > 0 ? 2.0 / (s.E_star_Pa * q) : 0.0;
    });
  }
  // Influence of a unit pressure on one pixel, at every offset (wrapped on the 2n grid). Love's
  // rectangle is even in both offsets: evaluated once per (|di|, |dj|).
  const double half = 0.5 * map.pixel_m;
  influence.resize((n + 1) * (n + 1));
  for_each_pixel((n + 1) * (n + 1), W, [&](std::size_t k) {
    const double i = static_cast<double>(k / (n + 1)), j = static_cast<double>(k % (n + 1));
    influence[k] = love_rectangle(j * map.pixel_m, i * map.pixel_m, half, half) / s.E_star_Pa;
  });
  return std::make_unique<PaddedConvolution>(n, influence, W);
}

// u ← f (u − τ r + K δ), δ the pressure jumps (beyond p_old − τ t) of the points clipped (p_old − τ t
// < 0 set to 0) or joining (p_old = 0 set to −τ g), in the order of their index; each row of u sums
// them in that order, so the bits do not depend on the number of threads.
class DirectCorrection {
 public:
  DirectCorrection(std::size_t n, const std::vector<double>& influence, Workers& w, bool periodic)
      : n_(n),
        influence_(influence),
        w_(w),
        acc_(static_cast<std::size_t>(w.count()), std::vector<double>(periodic ? 0 : n)) {}

  void update(const std::vector<double>& p0, const std::vector<double>& t0, const std::vector<double>& g0,
              const std::vector<double>& r, double tau, double f, std::vector<double>& u) {
    const std::size_t n = n_, nn = n * n;
    jumps_.clear();
    for (std::size_t k = 0; k < nn; ++k) {
      if (p0[k] > 0) {
        const double lin = p0[k] - tau * t0[k];
        if (lin < 0) jumps_.emplace_back(k, -lin);
      } else if (g0[k] < 0) {
        jumps_.emplace_back(k, -tau * g0[k]);
      }
    }
    // Rows in chunks of 8: each thread sums into its own row of `acc_`.
    constexpr std::size_t kRowChunk = 8;
    w_.run((n + kRowChunk - 1) / kRowChunk, nn >= kParallelFrom, [&](std::size_t c, std::size_t th) {
      std::vector<double>& a = acc_[th];
      for (std::size_t i = c * kRowChunk; i < std::min(n, (c + 1) * kRowChunk); ++i) {
        std::fill(a.begin(), a.end(), 0.0);
        for (const auto& [l, d] : jumps_) {
          const std::size_t r0 = l / n, b = l % n;
          const double* row = &influence_[(i > r0 ? i - r0 : r0 - i) * (n + 1)];
          for (std::size_t j = 0; j < b; ++j) a[j] += d * row[b - j];
          for (std::size_t j = b; j < n; ++j) a[j] += d * row[j - b];
        }
        double* uk = &u[i * n];
        const double* rk = &r[i * n];
        for (std::size_t j = 0; j < n; ++j) uk[j] = f * (uk[j] - tau * rk[j] + a[j]);
      }
    });
  }

 private:
  std::size_t n_;
  const std::vector<double>& influence_;
  Workers& w_;
  std::vector<std::pair<std::size_t, double>> jumps_;
  std::vector<std::vector<double>> acc_;  // per thread: one row of K δ
};

}  // namespace

NormalContact solve_normal_contact(const HeightMap& map, const NormalContactSettings& s) {
  check_inputs(map, s);
  const std::size_t n = map.n, nn = n * n;
  Workers W(s.threads);
  const double A = map.pixel_m * map.pixel_m;

  NormalContact out;
  std::vector<double>& p = out.pressure_Pa;
  start_pressures(map, s, out);
  std::vector<double> influence;  // isolated: the kernel at offsets (|di|, |dj|), (n + 1)², row |di|
  const std::unique_ptr<Convolution> convolution = make_convolution(map, s, W, influence);
  Convolution& K = *convolution;

  // Separation from the flat touching the highest summit.
  const double top = *std::max_element(map.h_m.begin(), map.h_m.end());
  std::vector<double> h0(nn);
  for (std::size_t k = 0; k < nn; ++k) h0[k] = top - map.h_m[k];

  std::vector<double> u(nn), g(nn), t(nn, 0.0), r(nn), p_old(nn);
  const double direct_max = std::max(2.0, static_cast<double>(std::bit_width(n)) * 4.0);
  DirectCorrection direct(n, influence, W, s.periodic);
  K.apply(p, u);
  out.convolutions = 1;
  double G_old = 1.0;
  bool delta = false;  // whether t may be conjugated with the last direction
  double gbar = 0;
  for (int it = 1; it <= s.max_iterations; ++it) {
    // u = K p here. Gap on the contact set, shifted by its mean there (the unknown approach).
    const auto [sum, count, square] = block_sums<3>(nn, W, [&](std::size_t k, auto& a) {
      g[k] = u[k] + h0[k];
      if (p[k] > 0) a[0] += g[k], a[1] += 1, a[2] += g[k] * g[k];
    });
    const double nc = count;
    gbar = nc > 0 ? sum / nc : 0.0;
    const double G = block_sums<1>(nn, W, [&](std::size_t k, auto& a) {
      g[k] -= gbar;
      if (p[k] > 0) a[0] += g[k] * g[k];
    })[0];
    // Conjugate direction on the contact set.
    const double beta = delta && G_old > 0 ? G / G_old : 0.0;  // G_old = 0: the last step was exact
    for_each_pixel(nn, W, [&](std::size_t k) { t[k] = p[k] > 0 ? g[k] + beta * t[k] : 0.0; });
    G_old = G;
    K.apply(t, r);
    ++out.convolutions;
    const double rsum = block_sums<1>(nn, W, [&](std::size_t k, auto& a) {
      if (p[k] > 0) a[0] += r[k];
    })[0];
    const double rbar = nc > 0 ? rsum / nc : 0.0;
    const auto [gt, rt] = block_sums<2>(nn, W, [&](std::size_t k, auto& a) {
      if (p[k] > 0) a[0] += g[k] * t[k], a[1] += (r[k] - rbar) * t[k];
    });
    // A gap flat on the contact to rounding (rms deviation ≤ 1e-12 of its rms) is the answer: a step
    // would be rounding over rounding (at Westergaard's full contact such steps grew until the CG
    // broke down).
    const bool exact = G <= 1e-24 * square;
    const double tau = rt != 0 && !exact ? gt / rt : 0.0;
    p_old.swap(p);
    // The step; points outside the contact that the flat overlaps join it. `changed` counts the
    // points where the new pressures are not p − τt (clipped at zero, or joining).
    const auto [total_p, changed] = block_sums<2>(nn, W, [&](std::size_t k, auto& a) {
      double x = 0;
      if (p_old[k] > 0) {
        x = p_old[k] - tau * t[k];
        if (x < 0) x = 0, a[1] += 1;
      } else if (g[k] < 0) {
        x = -tau * g[k];
        a[1] += 1;
      }
      p[k] = x;
      a[0] += x;
    });
    // Polonsky & Keer restart the conjugate directions whenever a point joins; here only the first
    // iteration is steepest descent. A few points joining at nearly every iteration (small spots at
    // the edges of a rough contact) kept the iteration at steepest descent, several times the
    // iterations for the same contact set and pressures (docs/performance.md).
    delta = true;
    // The load.
    const double total = total_p * A;
    if (!(total > 0)) throw std::runtime_error("normal contact: the pressures vanished (CG breakdown)");
    const double f = s.load_N / total;
    const double change = block_sums<1>(nn, W, [&](std::size_t k, auto& a) {
      p[k] *= f;
      a[0] += std::abs(p[k] - p_old[k]);
    })[0];
    out.iterations = it;
    out.residual = change * A / s.load_N;
    if (out.residual < s.tolerance) {
      out.converged = true;
      break;
    }
    // u = K p for the next iteration. Where no point was clipped or joined, p = f (p_old − τ t), so
    // K p = f (u − τ r) by linearity, without a convolution (within rounding: u is recomputed at the
    // end). Where a few points were (isolated contacts), p = f (p_old − τ t + δ) with δ nonzero at
    // those points only, and K p = f (u − τ r + K δ), K δ summed directly from the kernel (n² terms a
    // point): cheaper than a convolution up to about 4 log2(n) points, at the convolved pressures
    // within rounding (docs/topography.md, "Speed"; docs/performance.md).
    // Not for periodic maps: at Westergaard's exact full contact the steps are rounding over
    // rounding and the updated u drifted from K p until the CG broke down (a recomputed u stays at
    // rounding).
    if (changed == 0 && !s.periodic)
      for_each_pixel(nn, W, [&](std::size_t k) { u[k] = f * (u[k] - tau * r[k]); });
    else if (!s.periodic && changed <= direct_max)
      direct.update(p_old, t, g, r, tau, f, u);
    else
      K.apply(p, u), ++out.convolutions;
  }
  K.apply(p, u);
  ++out.convolutions;
  const auto [area_count, shift_sum] = block_sums<2>(nn, W, [&](std::size_t k, auto& a) {
    if (p[k] > 0) a[0] += 1, a[1] += u[k] + h0[k];
  });
  out.area_m2 = area_count * A;
  const double shift = area_count > 0 ? shift_sum / area_count : 0.0;  // u + h0 on the contact = approach
  out.approach_m = shift;
  out.gap_m.resize(nn);
  for (std::size_t k = 0; k < nn; ++k) out.gap_m[k] = std::max(0.0, u[k] + h0[k] - shift);
  return out;
}

}  // namespace asperity
