#include "generate/distributions.hpp"

#include <cmath>
#include <stdexcept>

#include "io/numbers.hpp"

namespace asperity {

namespace {

// ∫_{lo}^{hi} a^(q−1) da, with the q = 0 case ln(hi/lo); written through expm1 so that it is
// accurate for q near 0 as well.
double power_integral(double lo, double hi, double q) {
  const double L = std::log(hi / lo);
  if (q == 0.0) return L;
  return std::pow(lo, q) * std::expm1(q * L) / q;
}

}  // namespace

// ---- power law ------------------------------------------------------------------------
// With s = 1 − τ and r = a_max/a_min: F(a) = expm1(s ln(a/a_min)) / expm1(s ln r), so
// a(u) = a_min · exp( log1p(u · expm1(s ln r)) / s ); s = 0: a = a_min · r^u.

double PowerLaw::quantile(double u) const {
  const double s = 1.0 - tau;
  const double L = std::log(a_max / a_min);
  double a;
  if (s == 0.0)
    a = a_min * std::exp(u * L);
  else
    a = a_min * std::exp(std::log1p(u * std::expm1(s * L)) / s);
  return std::min(std::max(a, a_min), a_max);  // rounding never leaves the support
}

double PowerLaw::cdf(double a) const {
  if (a <= a_min) return 0.0;
  if (a >= a_max) return 1.0;
  const double s = 1.0 - tau;
  const double L = std::log(a_max / a_min), l = std::log(a / a_min);
  if (s == 0.0) return l / L;
  return std::expm1(s * l) / std::expm1(s * L);
}

double PowerLaw::moment(double k) const {
  const double s = 1.0 - tau;
  return power_integral(a_min, a_max, s + k) / power_integral(a_min, a_max, s);
}

// ---- lognormal ------------------------------------------------------------------------

double LogNormal::quantile(double u) const {
  const double mu = std::log(median);
  const double lo = a_min > 0.0 ? io::normal_cdf((std::log(a_min) - mu) / sigma_ln) : 0.0;
  const double hi = std::isfinite(a_max) ? io::normal_cdf((std::log(a_max) - mu) / sigma_ln) : 1.0;
  const double a = std::exp(mu + sigma_ln * io::normal_quantile(lo + u * (hi - lo)));
  return std::min(std::max(a, a_min), a_max);
}

double LogNormal::cdf(double a) const {
  if (a <= a_min || a <= 0.0) return 0.0;
  if (a >= a_max) return 1.0;
  const double mu = std::log(median);
  const double lo = a_min > 0.0 ? io::normal_cdf((std::log(a_min) - mu) / sigma_ln) : 0.0;
  const double hi = std::isfinite(a_max) ? io::normal_cdf((std::log(a_max) - mu) / sigma_ln) : 1.0;
  return (io::normal_cdf((std::log(a) - mu) / sigma_ln) - lo) / (hi - lo);
}

// ---- components and mixtures ------------------------------------------------------------

double component_quantile(const Component& c, double u) {
  return std::visit([u](const auto& d) { return d.quantile(u); }, c);
}

double component_cdf(const Component& c, double a) {
  return std::visit([a](const auto& d) { return d.cdf(a); }, c);
}

std::string describe(const Component& c) {
  struct V {
    std::string operator()(const PowerLaw& d) const {
      return "power law tau=" + io::format_significant(d.tau) + " on [" + io::format_significant(d.a_min) + ", " +
             io::format_significant(d.a_max) + "] m^2";
    }
    std::string operator()(const LogNormal& d) const {
      std::string s = "lognormal median=" + io::format_significant(d.median) +
                      " m^2 sigma_ln=" + io::format_significant(d.sigma_ln);
      if (d.a_min > 0.0 || std::isfinite(d.a_max))
        s += " truncated to [" + io::format_significant(d.a_min) + ", " + io::format_significant(d.a_max) + "] m^2";
      return s;
    }
    std::string operator()(const Fixed& d) const { return "fixed area=" + io::format_significant(d.area) + " m^2"; }
  };
  return std::visit(V{}, c);
}

double Mixture::weight(std::size_t j) const {
  double total = 0.0;
  for (double w : weights) total += w;
  return weights.at(j) / total;
}

std::size_t Mixture::pick(double u) const {
  double total = 0.0;
  for (double w : weights) total += w;
  const double target = u * total;
  double acc = 0.0;
  for (std::size_t j = 0; j + 1 < weights.size(); ++j) {
    acc += weights[j];
    if (target < acc) return j;
  }
  return weights.size() - 1;
}

double Mixture::quantile_of(std::size_t j, double u) const { return component_quantile(components.at(j), u); }

double Mixture::cdf(double a) const {
  double F = 0.0;
  for (std::size_t j = 0; j < components.size(); ++j) F += weight(j) * component_cdf(components[j], a);
  return F;
}

// ---- distribution -----------------------------------------------------------------------

double Distribution::draw(io::Uniform01& u) const {
  if (const auto* m = std::get_if<Mixture>(&family)) {
    const double u_pick = u();
    const double u_draw = u();
    return m->sample(u_pick, u_draw);
  }
  const double x = u();
  return std::visit(
      [x](const auto& d) -> double {
        if constexpr (std::is_same_v<std::decay_t<decltype(d)>, Mixture>)
          return 0.0;  // handled above
        else
          return d.quantile(x);
      },
      family);
}

double Distribution::cdf(double a) const {
  return std::visit([a](const auto& d) { return d.cdf(a); }, family);
}

std::string Distribution::describe() const {
  if (const auto* m = std::get_if<Mixture>(&family)) {
    std::string s = "mixture of";
    for (std::size_t j = 0; j < m->components.size(); ++j)
      s += (j ? "; " : " ") + io::format_significant(m->weight(j)) + " x " + asperity::describe(m->components[j]);
    return s;
  }
  return std::visit(
      [](const auto& d) -> std::string {
        if constexpr (std::is_same_v<std::decay_t<decltype(d)>, Mixture>)
          return {};
        else
          return asperity::describe(Component{d});
      },
      family);
}

namespace {

double normal_cdf_or_limit(double z) { return std::isinf(z) ? (z > 0 ? 1.0 : 0.0) : io::normal_cdf(z); }

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("distribution: " + what);
}

void validate_component(const Component& c) {
  struct V {
    void operator()(const PowerLaw& d) const {
      check(std::isfinite(d.tau), "power law tau must be finite");
      check(std::isfinite(d.a_min) && d.a_min > 0.0, "power law a_min must be > 0");
      check(std::isfinite(d.a_max) && d.a_max > d.a_min, "power law needs a_min < a_max < inf");
    }
    void operator()(const LogNormal& d) const {
      check(std::isfinite(d.median) && d.median > 0.0, "lognormal median must be > 0");
      check(std::isfinite(d.sigma_ln) && d.sigma_ln > 0.0, "lognormal sigma_ln must be > 0");
      check(d.a_min >= 0.0 && d.a_max > d.a_min, "lognormal needs 0 <= a_min < a_max");
      const double z_lo = d.a_min > 0.0 ? (std::log(d.a_min) - std::log(d.median)) / d.sigma_ln : -INFINITY;
      const double z_hi = std::isfinite(d.a_max) ? (std::log(d.a_max) - std::log(d.median)) / d.sigma_ln : INFINITY;
      check(normal_cdf_or_limit(z_hi) > normal_cdf_or_limit(z_lo),
            "lognormal truncation interval holds no probability");
    }
    void operator()(const Fixed& d) const { check(std::isfinite(d.area) && d.area > 0.0, "fixed area must be > 0"); }
  };
  std::visit(V{}, c);
}

}  // namespace

void validate(const Distribution& d) {
  if (const auto* m = std::get_if<Mixture>(&d.family)) {
    check(!m->components.empty(), "mixture needs at least one component");
    check(m->weights.size() == m->components.size(), "mixture needs one weight per component");
    for (double w : m->weights) check(std::isfinite(w) && w > 0.0, "mixture weights must be > 0");
    for (const auto& c : m->components) validate_component(c);
    return;
  }
  std::visit(
      [](const auto& x) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(x)>, Mixture>) validate_component(Component{x});
      },
      d.family);
}

JunctionPopulation draw_population(const Distribution& d, std::size_t n, std::uint64_t seed, double square_side_m) {
  validate(d);
  io::Uniform01 u(seed);
  JunctionPopulation pop;
  pop.area_m2.reserve(n);
  for (std::size_t i = 0; i < n; ++i) pop.area_m2.push_back(d.draw(u));
  if (square_side_m > 0.0) {
    pop.x_m.reserve(n);
    pop.y_m.reserve(n);
    for (std::size_t i = 0; i < n; ++i) {
      pop.x_m.push_back(square_side_m * u());
      pop.y_m.push_back(square_side_m * u());
    }
  }
  return pop;
}

}  // namespace asperity
