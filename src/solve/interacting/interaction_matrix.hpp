#pragma once
// The coupling of junctions through the half-space (docs/model.md §8): C_ij for i ≠ j, the mean
// x-displacement over junction i per unit x-force on junction j, each junction a disc of its
// initial area (radius sqrt(A0/π); the area lost under shear is second order in radius/distance
// and is neglected here). Dense and symmetric: N² doubles.
#include <cstddef>
#include <vector>

#include "solve/core/problem.hpp"

namespace asperity {

struct InteractionMatrix {
  std::size_t n = 0;
  std::vector<double> c;  // row-major n × n, m/N; zero diagonal and beyond the cut-off
  double operator()(std::size_t i, std::size_t j) const { return c[i * n + j]; }
};

// C_ij = disc_compliance of junctions i and j (physics/elastic_interaction.hpp), 0 for pairs
// farther apart than problem.interaction_cutoff when it is > 0. Needs problem.interacting().
InteractionMatrix interaction_matrix(const Problem& problem);

// The same C_ij, i > j only, written to buffer[i · ld + j] (row-major, the strict lower triangle;
// nothing else is touched): the fast solver keeps C there, beside G in the upper triangle of the
// same N × N buffer (N² doubles for both).
void fill_interaction_lower(const Problem& problem, double* buffer, std::size_t ld);

}  // namespace asperity
