#include "solve/interacting/interaction_matrix.hpp"

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
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
      const bool dropped = cutoff > 0 && std::hypot(dx, dy) > cutoff;
      buffer[i * ld + j] =
          dropped ? 0.0 : disc_compliance(dx, dy, radius[i], radius[j], p.law.E, p.law.nu, p.interaction_weighting);
    }
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
