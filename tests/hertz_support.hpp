#pragma once
// The smooth sphere on a flat of the contact tests (surface/normal_contact.hpp): its map, spanning
// `span` times Hertz's contact radius, and its normal solve at a tight tolerance.
#include <cmath>
#include <cstddef>

#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"

namespace asperity::testing {

// Hertz's contact radius a = (3PR / 4E*)^(1/3) [m].
inline double hertz_radius(double load_N, double radius_m, double E_star_Pa) {
  return std::cbrt(3 * load_N * radius_m / (4 * E_star_Pa));
}

// A sphere of radius R pressed with P into E*, on an n × n map spanning `span` · a.
inline NormalContact hertz_contact(std::size_t n, double radius_m, double load_N, double E_star_Pa, double span,
                                   HeightMap* map_out = nullptr) {
  HeightMap m;
  m.n = n;
  m.pixel_m = span * hertz_radius(load_N, radius_m, E_star_Pa) / static_cast<double>(n);
  m.h_m.assign(n * n, 0.0);
  add_sphere(m, radius_m);
  NormalContactSettings s;
  s.E_star_Pa = E_star_Pa;
  s.load_N = load_N;
  s.tolerance = 1e-12;
  NormalContact c = solve_normal_contact(m, s);
  if (map_out) *map_out = m;
  return c;
}

}  // namespace asperity::testing
