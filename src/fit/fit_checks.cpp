// Checks of a fit's inputs that need no YAML: objective names, NLopt algorithm names, and
// whether a measured A(Q) curve can be fitted at all (declared in fit_load.hpp).
#include <nlopt.hpp>

#include <cmath>
#include <cstdio>

#include "fit/fit_load.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"

namespace asperity {

using io::did_you_mean;
using io::format_significant;
using io::join;
using io::quote;

const char* objective_name(FitObjective o) {
  switch (o) {
    case FitObjective::quadratic_alpha:
      return "quadratic_alpha";
    case FitObjective::area_curve:
      return "area_curve";
    case FitObjective::stick_slip:
      return "stick_slip";
    case FitObjective::area_and_force:
      return "area_and_force";
    case FitObjective::user:
      return "user";
  }
  return "unknown";
}

const char* force_score_name(ForceScore s) {
  switch (s) {
    case ForceScore::pointwise:
      return "pointwise";
    case ForceScore::loading_and_cycles:
      return "loading_and_cycles";
    case ForceScore::loading_and_peaks:
      return "loading_and_peaks";
    case ForceScore::automatic:
      return "auto";
  }
  return "unknown";
}

std::string measured_curve_problem(const MeasuredCurve& curve, double A0_sum) {
  // Least squares of A = a + b x with x = Q² (b = −α), over the finite points.
  std::vector<double> x, y;
  for (std::size_t i = 0; i < curve.Q_N.size() && i < curve.A_m2.size(); ++i)
    if (std::isfinite(curve.Q_N[i]) && std::isfinite(curve.A_m2[i])) {
      x.push_back(curve.Q_N[i] * curve.Q_N[i]);
      y.push_back(curve.A_m2[i]);
    }
  const std::size_t n = x.size();
  if (n < 3) return "measured A(Q) has " + std::to_string(n) + " point(s); a fit needs at least 3";
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i];
  }
  mx /= static_cast<double>(n);
  my /= static_cast<double>(n);
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (!(sxx > 0)) return "measured A(Q) has a single value of Q; a fit needs A over a range of Q";
  const double b = sxy / sxx, a = my - b * mx;
  double ss_res = 0;
  for (std::size_t i = 0; i < n; ++i) ss_res += (y[i] - a - b * x[i]) * (y[i] - a - b * x[i]);
  const double se_alpha = std::sqrt(ss_res / static_cast<double>(n - 2) / sxx);
  const double alpha = -b;
  if (!(alpha > kMeasuredAlphaMinSigmas * se_alpha))
    return "measured A(Q) does not decrease with Q: the fit A = a - alpha Q^2 gives alpha = " +
           format_significant(alpha, 4) + " +- " + format_significant(se_alpha, 4) + " m^2/N^2 (a fit needs alpha > " +
           format_significant(kMeasuredAlphaMinSigmas, 4) + " standard errors)";
  if (!(std::abs(a / A0_sum - 1) <= kMeasuredA0Tolerance))
    return "measured A(Q = 0) = " + format_significant(a, 4) + " m^2 (intercept of A = a - alpha Q^2) is " +
           format_significant(a / A0_sum, 4) + " x the sum of the junction areas, " + format_significant(A0_sum, 4) +
           " m^2 (allowed: within " + format_significant(kMeasuredA0Tolerance * 100, 4) +
           " %; wrong unit or wrong file?)";
  return "";
}

std::string check_fit_algorithm(const std::string& name) {
  // By name over NLopt's list: nlopt_algorithm_from_string answers an unknown name with -1, which
  // is not a value of the enum (undefined behaviour to hold in one; UBSan, found by fuzz_fit).
  bool known = false;
  for (int i = 0; i < NLOPT_NUM_ALGORITHMS && !known; ++i) {
    const char* s = nlopt_algorithm_to_string(static_cast<nlopt_algorithm>(i));
    known = s && name == s;
  }
  if (!known) {
    std::vector<std::string> names;
    for (int i = 0; i < NLOPT_NUM_ALGORITHMS; ++i) {
      const char* s = nlopt_algorithm_to_string(static_cast<nlopt_algorithm>(i));
      // Only the ones a fit file can use (AUGLAG needs a subsidiary optimizer).
      if (s && std::string(s).rfind("LN_", 0) == 0 && std::string(s).find("AUGLAG") == std::string::npos)
        names.emplace_back(s);
    }
    return "unknown NLopt algorithm " + quote(name) + did_you_mean(name, names) +
           "; derivative-free local ones: " + join(names);
  }
  if (name.rfind("LD_", 0) == 0 || name.rfind("GD_", 0) == 0)
    return "NLopt algorithm " + quote(name) +
           " needs gradients, which a simulation does not give; use a derivative-free one (LN_*, GN_*)";
  if (name.find("AUGLAG") != std::string::npos || name.find("MLSL") != std::string::npos)
    return "NLopt algorithm " + quote(name) +
           " needs a subsidiary optimizer, which fit files do not set; use e.g. LN_BOBYQA";
  return "";
}

}  // namespace asperity
