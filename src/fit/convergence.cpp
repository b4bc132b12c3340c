#include "fit/convergence.hpp"

#include <boost/random/sobol.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "io/numbers.hpp"

namespace asperity {

namespace {

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

}  // namespace

std::vector<std::vector<double>> sobol_starts(std::size_t dims, std::size_t count, const std::vector<double>& avoid) {
  std::vector<std::vector<double>> out;
  if (dims == 0) return out;
  boost::random::sobol sobol(static_cast<unsigned>(dims));
  // (v − min)/(max − min + 1): the engine's integers onto [0, 1), exactly the dyadic points.
  const double range = static_cast<double>(sobol.max() - sobol.min()) + 1.0;
  bool first = true;
  while (out.size() < count) {
    std::vector<double> u(dims);
    for (double& x : u) x = static_cast<double>(sobol() - sobol.min()) / range;
    if (std::exchange(first, false)) continue;  // the centre
    if (!avoid.empty() && distance(u, avoid) < 1e-9) continue;
    out.push_back(std::move(u));
  }
  return out;
}

bool BasinRule::same_basin(double objective, double best, double scaled_distance) const {
  if (!std::isfinite(objective) || !std::isfinite(best)) return false;
  return objective - best <= relative * std::abs(best) || scaled_distance <= distance;
}

const char* converged_name(Converged c) {
  switch (c) {
    case Converged::yes:
      return "yes";
    case Converged::no:
      return "no";
    case Converged::unverified:
      return "unverified";
  }
  return "unknown";
}

ConvergenceVerdict judge_convergence(const std::vector<StartEnd>& ends, const BasinRule& rule) {
  ConvergenceVerdict v;
  v.in_best_basin.assign(ends.size(), false);
  double best = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < ends.size(); ++k)
    if (std::isfinite(ends[k].objective) && !(ends[k].objective >= best)) best = ends[k].objective, v.best = k;
  if (!std::isfinite(best)) {
    v.converged = ends.size() < 2 ? Converged::unverified : Converged::no;
    v.reason = "no start has a successful evaluation";
    return v;
  }
  for (std::size_t k = 0; k < ends.size(); ++k) {
    const double d = distance(ends[k].u, ends[v.best].u);
    if (!rule.same_basin(ends[k].objective, best, d)) continue;
    v.in_best_basin[k] = true;
    ++v.in_basin;
    v.spread = std::max(v.spread, d);
  }
  const std::string counted = std::to_string(v.in_basin) + " of " + std::to_string(ends.size()) +
                              " starts reached the best objective " + io::format_double(best) + " (within " +
                              io::format_double(rule.relative) + " relative, or " + io::format_double(rule.distance) +
                              " in the scaled coordinates)";
  if (ends.size() < 2) {
    v.converged = Converged::unverified;
    v.reason = "one start: nothing to compare its optimum with; set optimizer.starts >= 2 to certify it";
  } else if (v.in_basin >= 2) {
    v.converged = Converged::yes;
    v.reason = counted;
  } else {
    v.converged = Converged::no;
    v.reason = "only " + counted + ": no other start confirms it";
  }
  return v;
}

}  // namespace asperity
