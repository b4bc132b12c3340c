#pragma once
// The bound-constrained conjugate gradient of the tangential contact problems: minimises
// ½ qᵀKq − δ Σ q over the free entries of q (the others keep their values) with |q_k| ≤ bound_k,
// K symmetric positive definite (an elastic compliance). Its Karush–Kuhn–Tucker conditions are the
// stick and slip conditions of a quasi-static tangential contact: (Kq)_k = δ where |q_k| < bound_k
// (sticking), (Kq)_k ≤ δ where q_k = +bound_k (slipping). Polonsky & Keer's scheme (Wear 231, 1999)
// with a two-sided bound (Vollebregt, J. Optim. Theory Appl. 162, 2014): an entry at its bound whose
// gradient (Kq)_k − δ pushes it outward satisfies its slip condition and is left out of the step; the
// others (the free set F) take the conjugate step, clipped back to their bounds. As in the normal
// solve the directions are not restarted when F changes. Converged when max_F |(Kq)_k − δ| ≤
// tolerance · δ. Used on pixels (surface/tangential_contact.hpp, K an FFT convolution) and on
// junctions (K their compliance matrix).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "surface/pixel_loops.hpp"

namespace asperity {

struct BoundedCgSettings {
  double tolerance = 1e-10;
  int max_iterations = 5000;
};

struct BoundedCgResult {
  int iterations = 0;
  int products = 0;     // applications of K
  double residual = 0;  // max_F |(Kq)_k − δ| / δ at the end
  bool converged = false;
};

// apply(in, out): out = K in (both of q's size). bound: nullptr for no bound.
template <class Apply>
BoundedCgResult bounded_cg(Apply&& apply, double delta, const std::vector<unsigned char>& free,
                           const std::vector<double>* bound, std::vector<double>& q, const BoundedCgSettings& s,
                           pixel_loops::Workers& W) {
  using pixel_loops::block_sums;
  using pixel_loops::for_each_pixel;
  const std::size_t nn = q.size();
  BoundedCgResult res;
  std::vector<double> u(nn), g(nn, 0.0), d(nn, 0.0), w(nn);
  std::vector<unsigned char> in_F(nn, 0);
  apply(q, u);
  ++res.products;
  double G_old = 1.0;
  bool conjugate = false;
  for (int it = 1; it <= s.max_iterations + 1; ++it) {
    double worst = 0;
    for (std::size_t k = 0; k < nn; ++k) {
      in_F[k] = 0;
      if (!free[k]) continue;
      g[k] = u[k] - delta;
      if (bound && ((q[k] >= (*bound)[k] && g[k] <= 0) || (q[k] <= -(*bound)[k] && g[k] >= 0))) continue;
      in_F[k] = 1;
      worst = std::max(worst, std::abs(g[k]));
    }
    res.residual = worst / delta;
    if (worst <= s.tolerance * delta) {
      res.converged = true;
      break;
    }
    if (it > s.max_iterations) break;
    const double G = block_sums<1>(nn, W, [&](std::size_t k, auto& a) {
      if (in_F[k]) a[0] += g[k] * g[k];
    })[0];
    const double beta = conjugate && G_old > 0 ? G / G_old : 0.0;
    for_each_pixel(nn, W, [&](std::size_t k) { d[k] = in_F[k] ? g[k] + beta * d[k] : 0.0; });
    G_old = G;
    apply(d, w);
    ++res.products;
    const auto [gd, dw] = block_sums<2>(nn, W, [&](std::size_t k, auto& a) {
      if (in_F[k]) a[0] += g[k] * d[k], a[1] += d[k] * w[k];
    });
    if (!(dw > 0)) break;  // rounding: no descent left
    const double alpha = gd / dw;
    const double clipped = block_sums<1>(nn, W, [&](std::size_t k, auto& a) {
      if (!in_F[k]) return;
      double x = q[k] - alpha * d[k];
      if (bound && std::abs(x) > (*bound)[k]) x = std::copysign((*bound)[k], x), a[0] += 1;
      q[k] = x;
    })[0];
    conjugate = true;
    res.iterations = it;
    // u = K q: updated by linearity where no entry was clipped (within rounding), else recomputed.
    if (clipped == 0)
      for_each_pixel(nn, W, [&](std::size_t k) { u[k] -= alpha * w[k]; });
    else
      apply(q, u), ++res.products;
  }
  return res;
}

}  // namespace asperity
