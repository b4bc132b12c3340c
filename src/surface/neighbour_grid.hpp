#pragma once
// Points of the plane binned in square cells (a cell list): every point within `rings` cells of a
// place lies in the (2 rings + 1)² cells around it, so a search for near neighbours costs O(1) per
// point at an even density instead of O(N). The one cell list of the project: overlap checks of
// junction discs (scene/validate.cpp, generate/positions.cpp), the merge of overlapping discs
// (scene/topography_junctions.cpp) and the near pairs of the FFT coupling
// (solve/interacting/fft_coupling.cpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace asperity {

class NeighbourGrid {
 public:
  // cell_m > 0 [m]; extent_m: the largest |x| or |y| to come [m]. Cells no smaller than 1e-12 of
  // the extent keep every cell index far inside int64 (a larger cell only adds candidates).
  // Cells are hashed by their indices: unbounded, and filled one point at a time (a placement asks
  // before every point is known).
  explicit NeighbourGrid(double cell_m, double extent_m = 0.0);

  double cell() const { return cell_; }  // m, as used
  void insert(std::size_t i, double x_m, double y_m);
  // Removes point i, inserted at (x, y) (the same coordinates); absent: nothing. The other points
  // of its cell keep their order; the occupied cells' box is kept (it only bounds the search).
  void erase(std::size_t i, double x_m, double y_m);

  // visit(j) for every point j inserted in the (2 rings + 1)² cells around the cell of (x, y),
  // cell by cell in a fixed order, each cell's points in insertion order, until visit returns
  // false (then false). Safe from many threads at once while nobody inserts.
  template <class Visit>
  bool for_each_near(double x_m, double y_m, std::int64_t rings, Visit&& visit) const {
    // Only cells inside the occupied ones' bounding box: a wide ring costs no more than the grid.
    const std::int64_t cx = index(x_m), cy = index(y_m);
    for (std::int64_t gx = std::max(cx - rings, lo_x_); gx <= std::min(cx + rings, hi_x_); ++gx)
      for (std::int64_t gy = std::max(cy - rings, lo_y_); gy <= std::min(cy + rings, hi_y_); ++gy) {
        const auto it = cells_.find(key(gx, gy));
        if (it == cells_.end()) continue;
        for (const std::size_t j : it->second)
          if (!visit(j)) return false;
      }
    return true;
  }

 private:
  std::int64_t index(double v) const { return static_cast<std::int64_t>(std::floor(v / cell_)); }
  // Two cells may share a key only when their indices differ by 2^32: a far cell's points are
  // then candidates too, which the caller's distance test discards.
  static std::uint64_t key(std::int64_t cx, std::int64_t cy) {
    return (static_cast<std::uint64_t>(cx) << 32) ^ static_cast<std::uint32_t>(cy);
  }
  double cell_;
  std::int64_t lo_x_ = INT64_MAX, hi_x_ = INT64_MIN, lo_y_ = INT64_MAX, hi_y_ = INT64_MIN;  // occupied cells
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

}  // namespace asperity
