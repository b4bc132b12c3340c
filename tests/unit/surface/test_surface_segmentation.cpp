// surface/segmentation.hpp: contact clusters with their exact pixel areas and centroids, and the
// two connectivities.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "surface/segmentation.hpp"

using namespace asperity;

TEST_CASE("contact clusters: areas, centroids, order and connectivity", "[surface][segmentation]") {
  const std::size_t n = 10;
  const double px = 1e-6;
  std::vector<unsigned char> m(n * n, 0);
  auto set = [&](std::size_t i, std::size_t j) { m[i * n + j] = 1; };
  for (std::size_t i = 1; i <= 3; ++i)
    for (std::size_t j = 1; j <= 3; ++j) set(i, j);  // a 3 × 3 block: centroid pixel (2, 2)
  set(6, 6), set(7, 7);                              // two pixels touching by a corner
  set(8, 1);                                         // one pixel
  const auto eight = contact_clusters(m, n, px, Connectivity::eight);
  REQUIRE(eight.size() == 3);
  CHECK(eight[0].pixels == 9);
  CHECK(eight[0].area_m2 == 9 * px * px);
  // Centre of the grid at pixel 4.5: the block's centroid at (2 − 4.5) px in x and y.
  CHECK(eight[0].x_m == -2.5 * px);
  CHECK(eight[0].y_m == -2.5 * px);
  CHECK(eight[1].pixels == 2);  // the diagonal pair is one cluster with corners
  CHECK(eight[1].x_m == 2.0 * px);
  CHECK(eight[2].pixels == 1);
  CHECK(eight[2].x_m == -3.5 * px);
  CHECK(eight[2].y_m == 3.5 * px);
  const auto four = contact_clusters(m, n, px, Connectivity::four);
  REQUIRE(four.size() == 4);  // ... and two without
  double total = 0;
  for (const auto& c : four) total += c.area_m2;
  CHECK(std::abs(total / (12 * px * px) - 1) < 1e-15);
  CHECK(contact_clusters(std::vector<unsigned char>(n * n, 0), n, px, Connectivity::four).empty());
}
