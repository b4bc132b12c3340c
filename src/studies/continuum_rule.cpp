#include "studies/continuum_rule.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace asperity {

PopulationMeasures population_measures(const std::vector<double>& area, const std::vector<double>& x,
                                       const std::vector<double>& y) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = area.size();
  if (n < 2 || x.size() != n || y.size() != n) return {nan, nan};
  double A = 0, cx = 0, cy = 0;
  for (std::size_t i = 0; i < n; ++i) A += area[i], cx += area[i] * x[i], cy += area[i] * y[i];
  cx /= A, cy /= A;
  double rg2 = 0;
  for (std::size_t i = 0; i < n; ++i) rg2 += area[i] * ((x[i] - cx) * (x[i] - cx) + (y[i] - cy) * (y[i] - cy));
  rg2 /= A;
  if (!(rg2 > 0)) return {nan, nan};
  double radii = 0;
  for (const double a : area) radii += std::sqrt(a / std::numbers::pi);
  return {A / (2 * std::numbers::pi * rg2), radii / std::sqrt(2 * rg2)};
}

double StiffnessRule::error_at(double ratio) const { return prefactor * std::pow(ratio, exponent); }
double StiffnessRule::ratio_for(double error) const { return std::pow(error / prefactor, 1 / exponent); }

std::optional<StiffnessRule> fit_stiffness_rule(const std::vector<double>& ratio,
                                                const std::vector<double>& abs_error) {
  const std::size_t n = ratio.size();
  if (n < 2 || abs_error.size() != n) return std::nullopt;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  StiffnessRule r;
  r.ratio_min = ratio[0], r.ratio_max = ratio[0];
  for (std::size_t i = 0; i < n; ++i) {
    if (!(ratio[i] > 0) || !(abs_error[i] > 0)) return std::nullopt;
    const double lx = std::log(ratio[i]), ly = std::log(abs_error[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
    r.ratio_min = std::min(r.ratio_min, ratio[i]), r.ratio_max = std::max(r.ratio_max, ratio[i]);
  }
  const double N = static_cast<double>(n), det = N * sxx - sx * sx;
  if (!(det > 0)) return std::nullopt;
  r.exponent = (N * sxy - sx * sy) / det;
  r.prefactor = std::exp((sy - r.exponent * sx) / N);
  r.points = n;
  return r;
}

StiffnessRule independent_stiffness_rule() {
  StiffnessRule r;  // results/continuum/rule.csv (the test "the committed rule is the fit of the committed table")
  r.prefactor = 0.9316810295252447;
  r.exponent = 0.9544993226166115;
  r.ratio_min = 1.5064529758612137;
  r.ratio_max = 13.303957853369932;
  r.points = 9;
  return r;
}

}  // namespace asperity
