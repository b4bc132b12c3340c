#pragma once
// Junction-area distributions for the stand-in generator (docs/model.md §7).
//
// Every family is a small value type with an explicit inverse CDF, so a draw is
// quantile(uniform) of io/random.hpp's stream and the bytes of a generated population depend
// only on it and on the elementary functions of libm / Boost.Math.
#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "io/random.hpp"
#include "scene/scene.hpp"

namespace asperity {

// Truncated power law p(a) ∝ a^(−τ) on [a_min, a_max] (any real τ; τ = 1 is log-uniform).
struct PowerLaw {
  double tau = 1.5;
  double a_min = 1e-9, a_max = 1e-7;  // m²

  double quantile(double u) const;
  double cdf(double a) const;
  // k-th raw moment E[a^k] (closed form; k = 1: mean).
  double moment(double k) const;
  double mean() const { return moment(1.0); }
};

// Lognormal: ln a ~ Normal(ln median, sigma_ln²), optionally truncated to [a_min, a_max]
// (a_min = 0 and a_max = ∞ mean no truncation).
struct LogNormal {
  double median = 1e-8;  // m²
  double sigma_ln = 0.6;
  double a_min = 0.0;
  double a_max = std::numeric_limits<double>::infinity();

  double quantile(double u) const;
  double cdf(double a) const;
};

// Point mass: every junction has the same area (the equal-area limit, docs/model.md §6 claim 6).
struct Fixed {
  double area = 1e-8;  // m²
  double quantile(double) const { return area; }
  double cdf(double a) const { return a >= area ? 1.0 : 0.0; }
};

using Component = std::variant<PowerLaw, LogNormal, Fixed>;

// Finite mixture: one uniform picks the component (cumulative normalised weights, in order),
// a second one is passed to that component's quantile.
struct Mixture {
  std::vector<double> weights;        // > 0, normalised on use
  std::vector<Component> components;  // same length as weights

  // Index of the component chosen by u ∈ (0, 1).
  std::size_t pick(double u) const;
  double sample(double u_pick, double u_draw) const { return quantile_of(pick(u_pick), u_draw); }
  double quantile_of(std::size_t j, double u) const;
  double cdf(double a) const;
  double weight(std::size_t j) const;  // normalised
};

// A distribution of initial junction areas: one of the families above.
struct Distribution {
  std::variant<PowerLaw, LogNormal, Fixed, Mixture> family;

  // Draws one area, consuming one uniform (two for a mixture).
  double draw(io::Uniform01& u) const;
  double cdf(double a) const;
  // One line for provenance (README, experiment description), e.g.
  // "power law tau=1.5 on [1e-09, 1e-07] m^2".
  std::string describe() const;
};

double component_quantile(const Component& c, double u);
double component_cdf(const Component& c, double a);
std::string describe(const Component& c);

// Validates parameters (finite, ordered, positive, normalisable); throws std::invalid_argument.
void validate(const Distribution& d);

// n areas drawn from d with Uniform01(seed). When square_side_m > 0 (the field of view L),
// centre positions x_m, y_m are drawn afterwards, uniform in [0, L]², from the same stream —
// so the areas do not depend on whether positions are drawn.
JunctionPopulation draw_population(const Distribution& d, std::size_t n, std::uint64_t seed,
                                   double square_side_m = 0.0);

}  // namespace asperity
