#pragma once
// Whether a multi-start fit found its optimum (docs/calibration.md#convergence-several-starts):
// the design of starts in the optimizer's scaled box [0, 1]ⁿ, and the rule that says which
// starts ended in the best basin and whether that certifies the optimum. Plain numbers in and
// out; fit.cpp runs the starts.
#include <cstddef>
#include <string>
#include <vector>

namespace asperity {

// The first `count` points of the Sobol sequence in [0, 1]^dims (Boost's, deterministic: no
// generator state outlives the call), leaving out its first point, the centre of the box (the
// first lattice point of DIRECT: a start there would repeat the global phase's first point),
// and any point within 1e-9 of a coordinate-wise equal `avoid` (the file's start, already a
// start of its own).
std::vector<std::vector<double>> sobol_starts(std::size_t dims, std::size_t count,
                                              const std::vector<double>& avoid = {});

// A start ended in the best basin when its objective J is within `relative` of the best J*
// (J − J* ≤ relative·|J*|), or its optimum lies within `distance` of the best's (Euclidean, in
// the scaled coordinates): near J* = 0 (a model-generated, noise-free curve) J is quadratic in
// the parameters' error, so two starts stopped by xtol at the same point may differ in J by
// far more than any relative tolerance.
struct BasinRule {
  double relative = 1e-3;
  double distance = 1e-3;
  bool same_basin(double objective, double best, double scaled_distance) const;
};

// One start's end: its best point in scaled coordinates and its objective (NaN: no successful
// evaluation).
struct StartEnd {
  std::vector<double> u;
  double objective = 0;
};

enum class Converged { yes, no, unverified };
const char* converged_name(Converged c);  // "yes", "no", "unverified"

// The verdict over the starts. Certified (yes) when at least two starts ended in the best
// basin; no when there were two starts or more and only the best one did; unverified with a
// single start (nothing to compare it with: reported, not failed).
struct ConvergenceVerdict {
  Converged converged = Converged::unverified;
  std::size_t best = 0;             // index of the start with the lowest J (the first on ties)
  std::vector<bool> in_best_basin;  // per start
  int in_basin = 0;                 // how many (the best included)
  double spread = 0;                // largest scaled distance of a basin member from the best
  std::string reason;               // one line: why yes, no or unverified
};
ConvergenceVerdict judge_convergence(const std::vector<StartEnd>& ends, const BasinRule& rule);

}  // namespace asperity
