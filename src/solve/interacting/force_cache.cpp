#include "solve/interacting/force_cache.hpp"

#include <algorithm>
#include <cmath>

namespace asperity {

double hermite(double x0, double x1, double v0, double d0, double v1, double d1, double X, double* slope) {
  const double h = x1 - x0;
  const double t = (X - x0) / h;
  const double c2 = 3 * (v1 - v0) - h * (2 * d0 + d1);
  const double c3 = 2 * (v0 - v1) + h * (d0 + d1);
  if (slope) *slope = d0 + t * (2 * c2 + 3 * t * c3) / h;
  return v0 + t * (h * d0 + t * (c2 + t * c3));
}

const ForceNode& ForceCache::at(double X) {
  auto it = std::lower_bound(nodes_.begin(), nodes_.end(), X, [](const ForceNode& m, double x) { return m.X < x; });
  if (it != nodes_.end() && it->X == X) return *it;
  ForceNode fresh = solve_(X);
  it = std::lower_bound(nodes_.begin(), nodes_.end(), X, [](const ForceNode& m, double x) { return m.X < x; });
  return *nodes_.insert(it, std::move(fresh));
}

bool ForceCache::piece_ok(std::size_t s) const {
  const ForceNode& a = nodes_[s];
  const ForceNode& b = nodes_[s + 1];
  const double h = b.X - a.X;
  if (h <= 1e-13 * std::max(std::abs(a.X), std::abs(b.X))) return true;  // at the resolution of X
  // The Hermite piece's error is h^4 F''''/384; with F'''' ~ F'''/L (L = |F/F'|, the scale of X
  // on which F varies, smooth between events) and the cubic term c3 ~ h^3 F'''/6, it is about
  // c3 h/(64 L).
  const double L = (std::abs(a.F) + std::abs(b.F)) / (std::abs(a.dF) + std::abs(b.dF) + 1e-300);
  const double shrink = L > 0 ? std::min(1.0, h / (64 * L)) : 1.0;
  const double c3F = 2 * (a.F - b.F) + h * (a.dF + b.dF);
  const double c3A = 2 * (a.A - b.A) + h * (a.dA + b.dA);
  const double sF = std::max(std::abs(a.F), std::abs(b.F)) + 1e-300;
  const double sA = std::max(std::abs(a.A), std::abs(b.A)) + 1e-300;
  return std::abs(c3F) * shrink <= tol_ * sF && std::abs(c3A) * shrink <= tol_ * sA;
}

void ForceCache::refine() {
  for (std::size_t s = 0; s + 1 < nodes_.size();) {
    if (piece_ok(s)) {
      ++s;
      continue;
    }
    const double mid = 0.5 * (nodes_[s].X + nodes_[s + 1].X);
    ForceNode m = solve_(mid);
    nodes_.insert(nodes_.begin() + static_cast<std::ptrdiff_t>(s + 1), std::move(m));
  }
}

std::size_t ForceCache::continuation_node(double X, double x_up) const {
  // Past the next slip position (an integrator stage beyond the event, which the event then cuts
  // off) the set has changed, so the current set's F(X) there is only a smooth continuation for
  // the step's stages: the cubic Hermite from a node at least as far behind the last node as X
  // is ahead of it, continued (value and slope continuous at the slip position; no solve).
  // Farther out, or with too short a cache, nothing (a solve): a cubic continued well beyond its
  // interval drifts off, and a step taken on it would wander.
  const std::size_t m = nodes_.size();
  if (m < 2 || !(X > nodes_.back().X) || !(nodes_.back().X >= x_up)) return npos;
  const double d = X - nodes_.back().X;
  for (std::size_t a = m - 1; a-- > 0;)
    if (nodes_.back().X - nodes_[a].X >= d) return a;
  return npos;
}

std::size_t ForceCache::covering_piece(double X, double x_up, double x_down) {
  if (X < nodes_.front().X || X > nodes_.back().X) {
    // Extend past X by the cache's width (a slider oscillation comes back), within the slip
    // positions: beyond them the set changes.
    const double lo = nodes_.front().X, hi = nodes_.back().X;
    const double w = hi - lo;
    double target;
    if (X < lo) {
      target = X - std::max(w, lo - X);
      if (std::isfinite(x_down) && X >= x_down) target = std::max(target, x_down);
    } else {
      target = X + std::max(w, X - hi);
      if (std::isfinite(x_up) && X <= x_up) target = std::min(target, x_up);
    }
    // Past a slip position (an integrator stage beyond the event): twice as far as asked, so
    // a step's stages there need few nodes, and never deep into the range beyond (where the
    // set would have changed and Eq. (3) junctions approach their force limit).
    if (X > x_up) target = X + 2 * (X - hi);
    if (X < x_down) target = X - 2 * (lo - X);
    at(target);
    refine();
  }
  if (nodes_.size() == 1) return 0;
  auto it = std::upper_bound(nodes_.begin(), nodes_.end(), X, [](double x, const ForceNode& m) { return x < m.X; });
  std::size_t s = static_cast<std::size_t>(it - nodes_.begin());
  s = s == 0 ? 0 : s - 1;
  return std::min(s, nodes_.size() - 2);
}

double ForceCache::value(double X, double ForceNode::*value, double ForceNode::*slope, double x_up, double x_down) {
  if (const std::size_t c = continuation_node(X, x_up); c != npos) {
    const ForceNode& a = nodes_[c];
    const ForceNode& b = nodes_.back();
    return hermite(a.X, b.X, a.*value, a.*slope, b.*value, b.*slope, X);
  }
  const std::size_t s = covering_piece(X, x_up, x_down);
  if (nodes_.size() == 1) return nodes_[0].*value + nodes_[0].*slope * (X - nodes_[0].X);
  const ForceNode& a = nodes_[s];
  const ForceNode& b = nodes_[s + 1];
  return hermite(a.X, b.X, a.*value, a.*slope, b.*value, b.*slope, X);
}

}  // namespace asperity
