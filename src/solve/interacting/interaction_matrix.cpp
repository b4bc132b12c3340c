#include "solve/interacting/interaction_matrix.hpp"

#include <atomic>
#include <cmath>
#include <stdexcept>

#include "physics/contact_law.hpp"
#include "physics/elastic_interaction.hpp"

namespace asperity {

void fill_interaction_lower(const Problem& p, double* buffer, std::size_t ld) {
  if (!p.interacting()) throw std::logic_error("interaction_matrix: the problem has no junction positions");
  const std::size_t n = p.size();
  std::vector<double> radius(n);
  for (std::size_t i = 0; i < n; ++i) radius[i] = disc_radius(p.A0[i]);
  const double cutoff = p.interaction_cutoff;
  // Rows in parallel (each entry written once: the same matrix on any number of threads). No
  // exception may leave the parallel loop: an overlap (refused when the scene loads) is flagged
  // there and thrown after it.
  std::atomic<bool> overlap{false};
#pragma omp parallel for schedule(dynamic, 16)
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j], d = std::hypot(dx, dy);
      const bool dropped = cutoff > 0 && d > cutoff;
      if (!dropped && !(d >= radius[i] + radius[j])) {
        overlap = true;
        continue;
      }
      buffer[i * ld + j] = dropped ? 0.0
                                   : disc_compliance_at_distance(dx, dy, d, radius[i], radius[j], p.law.E, p.law.nu,
                                                                 p.interaction_weighting);
    }
  if (overlap) throw std::invalid_argument("disc_compliance: discs overlap or radii are invalid");
}

InteractionMatrix interaction_matrix(const Problem& p) {
  const std::size_t n = p.size();
  InteractionMatrix m{n, std::vector<double>(n * n, 0.0)};
  fill_interaction_lower(p, m.c.data(), n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < i; ++j) m.c[j * n + i] = m.c[i * n + j];
  return m;
}

}  // namespace asperity
