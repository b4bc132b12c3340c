#include "surface/neighbour_grid.hpp"

#include <algorithm>
#include <stdexcept>

namespace asperity {

NeighbourGrid::NeighbourGrid(double cell_m, double extent_m) : cell_(std::max(cell_m, std::abs(extent_m) * 1e-12)) {
  if (!(cell_ > 0) || !std::isfinite(cell_)) throw std::invalid_argument("NeighbourGrid: the cell size must be > 0");
}

void NeighbourGrid::insert(std::size_t i, double x_m, double y_m) {
  const std::int64_t cx = index(x_m), cy = index(y_m);
  lo_x_ = std::min(lo_x_, cx), hi_x_ = std::max(hi_x_, cx);
  lo_y_ = std::min(lo_y_, cy), hi_y_ = std::max(hi_y_, cy);
  cells_[key(cx, cy)].push_back(i);
}

void NeighbourGrid::erase(std::size_t i, double x_m, double y_m) {
  const auto it = cells_.find(key(index(x_m), index(y_m)));
  if (it == cells_.end()) return;
  std::vector<std::size_t>& v = it->second;
  if (const auto at = std::find(v.begin(), v.end(), i); at != v.end()) v.erase(at);
}

}  // namespace asperity
