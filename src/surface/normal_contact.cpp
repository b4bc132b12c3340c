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

// The conjugate-gradient iteration of Polonsky & Keer on the pressures `out.pressure_Pa`, with
// u = K p kept up to date between iterations.
class PressureCg {
 public:
  PressureCg(const HeightMap& map, const NormalContactSettings& s, Workers& W, Convolution& K,
             const std::vector<double>& influence, NormalContact& out)
      : s_(s),
        nn_(map.n * map.n),
        A_(map.pixel_m * map.pixel_m),
        W_(W),
        K_(K),
        out_(out),
        p_(out.pressure_Pa),
        h0_(separation_from_top(map)),
        u_(nn_),
        g_(nn_),
        t_(nn_, 0.0),
        r_(nn_),
        p_old_(nn_),
        direct_max_(std::max(2.0, static_cast<double>(std::bit_width(map.n)) * 4.0)),
        direct_(map.n, influence, W, s.periodic) {
    K_.apply(p_, u_);
    out_.convolutions = 1;
  }

  // Iteration `it`; true once the pressures have converged.
  bool iterate(int it) {
    double count = 0, square = 0;
    const double G = shifted_gap(count, square);
    const double tau = step_length(G, count, square);
    p_old_.swap(p_);
    const auto [total_p, changed] = take_step(tau);
    // Polonsky & Keer restart the conjugate directions whenever a point joins; here only the first
    // iteration is steepest descent. A few points joining at nearly every iteration (small spots at
    // the edges of a rough contact) kept the iteration at steepest descent, several times the
    // iterations for the same contact set and pressures (docs/performance.md).
    delta_ = true;
    const double f = scale_to_load(total_p);
    out_.iterations = it;
    if (out_.residual < s_.tolerance) {
      out_.converged = true;
      return true;
    }
    update_displacements(changed, tau, f);
    return false;
  }

  // The contact area, the approach and the gap of the final pressures.
  void finish() {
    const std::size_t nn = nn_;
    K_.apply(p_, u_);
    ++out_.convolutions;
    const auto [area_count, shift_sum] = block_sums<2>(nn, W_, [&](std::size_t k, auto& a) {
      if (p_[k] > 0) a[0] += 1, a[1] += u_[k] + h0_[k];
    });
    out_.area_m2 = area_count * A_;
    const double shift = area_count > 0 ? shift_sum / area_count : 0.0;  // u + h0 on the contact = approach
    out_.approach_m = shift;
    out_.gap_m.resize(nn);
    for (std::size_t k = 0; k < nn; ++k) out_.gap_m[k] = std::max(0.0, u_[k] + h0_[k] - shift);
  }

 private:
  // Separation from the flat touching the highest summit.
  static std::vector<double> separation_from_top(const HeightMap& map) {
    const std::size_t nn = map.n * map.n;
    const double top = *std::max_element(map.h_m.begin(), map.h_m.end());
    std::vector<double> h0(nn);
    for (std::size_t k = 0; k < nn; ++k) h0[k] = top - map.h_m[k];
    return h0;
  }

  // u = K p here. Gap on the contact set, shifted by its mean there (the unknown approach); returns
  // its squared norm there, with the contact's point count and the squared norm before the shift.
  double shifted_gap(double& count, double& square) {
    const std::size_t nn = nn_;
    const auto [sum, n_contact, sum_square] = block_sums<3>(nn, W_, [&](std::size_t k, auto& a) {
      g_[k] = u_[k] + h0_[k];
      if (p_[k] > 0) a[0] += g_[k], a[1] += 1, a[2] += g_[k] * g_[k];
    });
    count = n_contact;
    square = sum_square;
    const double gbar = count > 0 ? sum / count : 0.0;
    return block_sums<1>(nn, W_, [&](std::size_t k, auto& a) {
      g_[k] -= gbar;
      if (p_[k] > 0) a[0] += g_[k] * g_[k];
    })[0];
  }

  // The conjugate direction t on the contact set, r = K t, and the step length along t.
  double step_length(double G, double nc, double square) {
    const std::size_t nn = nn_;
    const double beta = delta_ && G_old_ > 0 ? G / G_old_ : 0.0;  // G_old = 0: the last step was exact
    for_each_pixel(nn, W_, [&](std::size_t k) { t_[k] = p_[k] > 0 ? g_[k] + beta * t_[k] : 0.0; });
    G_old_ = G;
    K_.apply(t_, r_);
    ++out_.convolutions;
    const double rsum = block_sums<1>(nn, W_, [&](std::size_t k, auto& a) {
      if (p_[k] > 0) a[0] += r_[k];
    })[0];
    const double rbar = nc > 0 ? rsum / nc : 0.0;
    const auto [gt, rt] = block_sums<2>(nn, W_, [&](std::size_t k, auto& a) {
      if (p_[k] > 0) a[0] += g_[k] * t_[k], a[1] += (r_[k] - rbar) * t_[k];
    });
    // A gap flat on the contact to rounding (rms deviation ≤ 1e-12 of its rms) is the answer: a step
    // would be rounding over rounding (at Westergaard's full contact such steps grew until the CG
    // broke down).
    const bool exact = G <= 1e-24 * square;
    return rt != 0 && !exact ? gt / rt : 0.0;
  }

  // The step from p_old; points outside the contact that the flat overlaps join it. Returns the sum
  // of the new pressures and the count of points where they are not p − τt (clipped at zero, or
  // joining).
  std::array<double, 2> take_step(double tau) {
    return block_sums<2>(nn_, W_, [&](std::size_t k, auto& a) {
      double x = 0;
      if (p_old_[k] > 0) {
        x = p_old_[k] - tau * t_[k];
        if (x < 0) x = 0, a[1] += 1;
      } else if (g_[k] < 0) {
        x = -tau * g_[k];
        a[1] += 1;
      }
      p_[k] = x;
      a[0] += x;
    });
  }

  // Scales the pressures to the load; returns the factor and sets the residual (the relative change
  // of the pressures).
  double scale_to_load(double total_p) {
    const double total = total_p * A_;
    if (!(total > 0)) throw std::runtime_error("normal contact: the pressures vanished (CG breakdown)");
    const double f = s_.load_N / total;
    const double change = block_sums<1>(nn_, W_, [&](std::size_t k, auto& a) {
      p_[k] *= f;
      a[0] += std::abs(p_[k] - p_old_[k]);
    })[0];
    out_.residual = change * A_ / s_.load_N;
    return f;
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
  void update_displacements(double changed, double tau, double f) {
    if (changed == 0 && !s_.periodic)
      for_each_pixel(nn_, W_, [&](std::size_t k) { u_[k] = f * (u_[k] - tau * r_[k]); });
    else if (!s_.periodic && changed <= direct_max_)
      direct_.update(p_old_, t_, g_, r_, tau, f, u_);
    else
      K_.apply(p_, u_), ++out_.convolutions;
  }

  const NormalContactSettings& s_;
  const std::size_t nn_;
  const double A_;  // pixel area
  Workers& W_;
  Convolution& K_;
  NormalContact& out_;
  std::vector<double>& p_;
  const std::vector<double> h0_;
  std::vector<double> u_, g_, t_, r_, p_old_;
  const double direct_max_;
  DirectCorrection direct_;
  double G_old_ = 1.0;
  bool delta_ = false;  // whether t may be conjugated with the last direction
};

}  // namespace

NormalContact solve_normal_contact(const HeightMap& map, const NormalContactSettings& s) {
  check_inputs(map, s);
  Workers W(s.threads);
  NormalContact out;
  start_pressures(map, s, out);
  std::vector<double> influence;  // isolated: the kernel at offsets (|di|, |dj|), (n + 1)², row |di|
  const std::unique_ptr<Convolution> convolution = make_convolution(map, s, W, influence);
  PressureCg cg(map, s, W, *convolution, influence, out);
  for (int it = 1; it <= s.max_iterations; ++it)
    if (cg.iterate(it)) break;
  cg.finish();
  return out;
}

}  // namespace asperity
