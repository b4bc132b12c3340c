// surface/neighbour_grid.hpp: the cell list finds every point within rings · cell of a place,
// checked against all pairs by brute force.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "surface/neighbour_grid.hpp"

namespace asperity {
namespace {

// Points within `reach` of (x, y) found through the grid, and by looking at every point.
// `visited` counts the candidates the grid offered.
std::set<std::size_t> near_by_grid(const NeighbourGrid& g, const std::vector<double>& x, const std::vector<double>& y,
                                   double px, double py, double reach, std::int64_t rings,
                                   std::size_t* visited = nullptr) {
  std::set<std::size_t> found;
  g.for_each_near(px, py, rings, [&](std::size_t j) {
    if (visited) ++*visited;
    if (std::hypot(px - x[j], py - y[j]) < reach) found.insert(j);
    return true;
  });
  return found;
}
std::set<std::size_t> near_by_all(const std::vector<double>& x, const std::vector<double>& y, double px, double py,
                                  double reach) {
  std::set<std::size_t> found;
  for (std::size_t j = 0; j < x.size(); ++j)
    if (std::hypot(px - x[j], py - y[j]) < reach) found.insert(j);
  return found;
}

}  // namespace

TEST_CASE("the neighbour grid finds every point within rings cells, as all pairs do", "[surface]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3e-3, 2e-3);  // both signs: cells below zero too
  std::vector<double> x, y;
  for (int i = 0; i < 2000; ++i) x.push_back(u(rng)), y.push_back(u(rng));
  for (int i = 0; i < 200; ++i) x.push_back(1e-3 + 1e-6 * u(rng)), y.push_back(-1e-3 + 1e-6 * u(rng));  // a cluster
  const double cell = 1e-4;
  NeighbourGrid g(cell);
  for (std::size_t j = 0; j < x.size(); ++j) g.insert(j, x[j], y[j]);
  std::size_t compared = 0, pairs = 0, visited_1 = 0;
  for (const std::int64_t rings : {1, 3}) {
    const double reach = rings * cell;
    for (std::size_t i = 0; i < x.size(); i += 7) {
      const auto a = near_by_grid(g, x, y, x[i], y[i], reach, rings, rings == 1 ? &visited_1 : nullptr);
      const auto b = near_by_all(x, y, x[i], y[i], reach);
      CHECK(a == b);
      ++compared;
      pairs += b.size();
    }
  }
  CHECK(pairs > 3000);  // the searches found many neighbours, the cluster's among them
  // A cell list's point: each search looks at the few points of 3 x 3 cells (at this density
  // about 7, plus the cluster's 200 for the searches beside it), not at all 2,200.
  const double per_search = static_cast<double>(visited_1) / static_cast<double>(compared / 2);
  INFO("candidates per search at rings 1: " << per_search);
  CHECK(per_search < 80);
}

TEST_CASE("the neighbour grid stops when asked and keeps wide rings to the occupied cells", "[surface]") {
  NeighbourGrid g(1.0);
  for (std::size_t j = 0; j < 10; ++j) g.insert(j, 0.5, 0.5);
  int seen = 0;
  CHECK_FALSE(g.for_each_near(0.5, 0.5, 1, [&](std::size_t) { return ++seen < 3; }));
  CHECK(seen == 3);
  // A ring of 10^6 cells looks at the one occupied cell, not at 4·10^12 empty ones.
  seen = 0;
  CHECK(g.for_each_near(0.5, 0.5, 1000000, [&](std::size_t) { return ++seen, true; }));
  CHECK(seen == 10);
}

TEST_CASE("the neighbour grid keeps far-apart points apart and refuses a cell of zero", "[surface]") {
  // Two pairs 1e7 m apart, cells of 1 µm: the extent widens the cells to 1e-5 m, every index
  // stays far inside int64, and each pair finds only itself.
  const std::vector<double> x{0.0, 3e-7, 1e7, 1e7 + 3e-7}, y{0.0, 0.0, -1e7, -1e7};
  NeighbourGrid g(1e-6, 1e7);
  CHECK(g.cell() == Approx(1e-5).epsilon(1e-12));
  for (std::size_t j = 0; j < x.size(); ++j) g.insert(j, x[j], y[j]);
  CHECK(near_by_grid(g, x, y, x[0], y[0], 1e-5, 1) == std::set<std::size_t>{0, 1});
  CHECK(near_by_grid(g, x, y, x[3], y[3], 1e-5, 1) == std::set<std::size_t>{2, 3});
  CHECK_THROWS_AS(NeighbourGrid(0.0), std::invalid_argument);
  CHECK_THROWS_AS(NeighbourGrid(std::nan("")), std::invalid_argument);
}

TEST_CASE("points erased from the neighbour grid are no longer found; the others keep their order", "[surface]") {
  NeighbourGrid g(1.0);
  for (std::size_t j = 0; j < 5; ++j) g.insert(j, 0.5, 0.5);  // one cell
  g.insert(5, 2.5, 0.5);
  g.erase(2, 0.5, 0.5);
  g.erase(5, 2.5, 0.5);
  g.erase(7, 0.5, 0.5);  // never inserted: nothing
  std::vector<std::size_t> seen;
  g.for_each_near(0.5, 0.5, 2, [&](std::size_t j) {
    seen.push_back(j);
    return true;
  });
  CHECK(seen == std::vector<std::size_t>{0, 1, 3, 4});
}

}  // namespace asperity
