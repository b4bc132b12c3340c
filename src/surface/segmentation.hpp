#pragma once
// Contact clusters: the connected components of the pixels in contact (pressure > 0), each a
// junction of the asperity model with its area and centroid (relative to the map's centre, the
// positions the interaction kernel uses).
#include <cstddef>
#include <vector>

#include "surface/height_map.hpp"

namespace asperity {

enum class Connectivity { four, eight };  // edge neighbours only, or corners too

struct ContactCluster {
  std::size_t pixels = 0;
  double area_m2 = 0;
  double x_m = 0, y_m = 0;  // centroid, from the centre of the grid
};

// Clusters of `in_contact` (n × n, row-major, nonzero = in contact) on a grid of `pixel_m`,
// largest first (ties by centroid x, then y: a reproducible order). Not periodic.
std::vector<ContactCluster> contact_clusters(const std::vector<unsigned char>& in_contact, std::size_t n,
                                             double pixel_m, Connectivity connectivity);

}  // namespace asperity
