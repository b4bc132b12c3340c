#pragma once
// Anderson acceleration (type II, Walker & Ni 2011) of a fixed-point iteration z ← g(z): the
// next iterate is g(z) − ΔG γ, with γ the least-squares fit of the current residual g(z) − z by
// the differences of the last `depth` residuals. For a map that is nearly linear and contracts
// linearly (the interacting solver's chord iteration), a few residuals span the slow directions
// and the iteration converges in fewer evaluations of g.
#include <cstddef>
#include <deque>
#include <vector>

namespace asperity {

class Anderson {
 public:
  explicit Anderson(std::size_t n, std::size_t depth = 3) : n_(n), depth_(depth) {}

  // z: the current iterate, g: the map's image g(z) (both of size n). When the history allows,
  // g is overwritten by the accelerated iterate and true returned; false leaves g as it is
  // (the plain step), e.g. at the first call after clear() or when the fit is ill-posed.
  bool step(const std::vector<double>& z, std::vector<double>& g);
  void clear();  // forget the history (the map changed, or a step was damped)

 private:
  std::size_t n_, depth_;
  bool has_prev_ = false;
  std::vector<double> r_prev_, g_prev_;
  std::deque<std::vector<double>> dR_, dG_;  // differences of residuals and images, newest last
};

}  // namespace asperity
