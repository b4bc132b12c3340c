#pragma once
// Between events the interacting population's total force F(X) and area A(X) are smooth
// functions of X alone. The cache keeps exact solves of the pinned set (nodes) sorted by X and
// answers F(X), A(X) from their piecewise cubic Hermite interpolants, refined until each piece's
// estimated error is below the tolerance; past the next slip position (an integrator stage
// beyond the event) it continues the last pieces instead of solving. Every change of the pinned
// set clears it.
#include <cstddef>
#include <functional>
#include <vector>

namespace asperity {

// An exact solve of the pinned set at X: totals and their X-derivatives, and per position of P
// the force f [N] and df/dX [N/m].
struct ForceNode {
  double X = 0, F = 0, dF = 0, A = 0, dA = 0;
  std::vector<double> f, a;
};

// Cubic Hermite on [x0, x1] from values and slopes at both ends, at X (also outside, continued);
// its slope there in *slope when asked.
double hermite(double x0, double x1, double v0, double d0, double v1, double d1, double X, double* slope = nullptr);

class ForceCache {
 public:
  using Solve = std::function<ForceNode(double)>;  // the exact solve at X of the current set
  // tolerance: relative error of a piece's F and A.
  ForceCache(Solve solve, double tolerance) : solve_(std::move(solve)), tol_(tolerance) {}

  const std::vector<ForceNode>& nodes() const { return nodes_; }
  void clear() { nodes_.clear(); }
  const ForceNode& at(double X);  // the node at X, solved and inserted if needed
  void refine();                  // splits every piece whose estimated error is over the tolerance
  // F(X) or A(X) (the value and slope members of ForceNode) from the pieces, or their
  // continuation past the next slip; x_up, x_down: the next slip positions above and below.
  double value(double X, double ForceNode::*value, double ForceNode::*slope, double x_up, double x_down);

 private:
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);
  bool piece_ok(std::size_t s) const;
  std::size_t continuation_node(double X, double x_up) const;        // npos: none
  std::size_t covering_piece(double X, double x_up, double x_down);  // extends and refines to cover X

  Solve solve_;
  double tol_;
  std::vector<ForceNode> nodes_;  // sorted by X
};

}  // namespace asperity
