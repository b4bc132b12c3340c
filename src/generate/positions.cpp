#include "generate/positions.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "generate/distributions.hpp"
#include "io/numbers.hpp"
#include "physics/contact_law.hpp"
#include "surface/neighbour_grid.hpp"

namespace asperity {

Positions place_in_contact_disc(const std::vector<double>& areas, double R, std::uint64_t seed, int max_tries) {
  if (!(R > 0) || !std::isfinite(R)) throw std::invalid_argument("contact radius must be > 0");
  const std::size_t n = areas.size();
  std::vector<double> radius(n);
  double r_max = 0;
  for (std::size_t i = 0; i < n; ++i) r_max = std::max(r_max, radius[i] = disc_radius(areas[i]));
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return areas[a] > areas[b]; });

  // Placed junctions in cells of the largest diameter: an overlap can only be with a junction of
  // the 3 × 3 cells around a candidate.
  NeighbourGrid grid(2 * r_max, R);
  Positions p{std::vector<double>(n), std::vector<double>(n)};
  io::Uniform01 u(seed);
  for (const std::size_t i : order) {
    bool placed = false;
    for (int attempt = 0; attempt < max_tries && !placed; ++attempt) {
      const double sx = 2 * u() - 1, sy = 2 * u() - 1, keep = u();
      const double s2 = sx * sx + sy * sy;
      if (s2 >= 1 || keep * keep > 1 - s2) continue;  // outside the disc, or thinned to the Hertz density
      const double x = R * sx, y = R * sy;
      // A relative margin of 1e-12 keeps touching pairs clear of the loader's overlap test
      // (which computes the distance with hypot).
      const bool free = grid.for_each_near(x, y, 1, [&](std::size_t j) {
        const double ddx = x - p.x_m[j], ddy = y - p.y_m[j], reach = (radius[i] + radius[j]) * (1 + 1e-12);
        return ddx * ddx + ddy * ddy >= reach * reach;
      });
      if (!free) continue;
      p.x_m[i] = x;
      p.y_m[i] = y;
      grid.insert(i, x, y);
      placed = true;
    }
    if (!placed)
      throw std::invalid_argument("no room for junction " + std::to_string(i + 1) + " (area " +
                                  io::format_short(areas[i]) + " m^2) in a contact disc of radius " +
                                  io::format_short(R) + " m after " + std::to_string(max_tries) +
                                  " draws: the junctions cover too much of it; raise the contact radius");
  }
  return p;
}

}  // namespace asperity
