#include "campaign/campaign.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "io/numbers.hpp"

namespace asperity {

AxisValue Axis::value(std::uint64_t i) const {
  if (i >= size()) throw std::out_of_range("axis " + key + ": value index out of range");
  if (kind == Kind::list) return values[i];
  double x = a;
  if (n > 1) {
    if (i + 1 == n) {
      x = b;  // exact end point, whatever the rounding of the formula
    } else {
      const double f = static_cast<double>(i) / static_cast<double>(n - 1);
      x = kind == Kind::linspace ? a + (b - a) * f : a * std::pow(b / a, f);
    }
  }
  return AxisValue{true, false, x, io::format_double(x)};
}

std::uint64_t Grid::size() const {
  if (axes.empty()) return 1;
  if (combine == Combine::zip) return axes.front().size();
  std::uint64_t s = 1;
  for (const Axis& ax : axes) s *= ax.size();  // overflow rejected by the loader
  return s;
}

std::uint64_t Campaign::size() const {
  std::uint64_t s = 0;
  for (const Grid& g : grids) s += g.size() * scenes.size();
  return s;
}

std::vector<std::string> Campaign::varied_keys() const {
  std::vector<std::string> keys;
  for (const Grid& g : grids)
    for (const Axis& ax : g.axes)
      if (std::find(keys.begin(), keys.end(), ax.key) == keys.end()) keys.push_back(ax.key);
  return keys;
}

Point point_at(const Campaign& c, std::uint64_t index) {
  std::uint64_t j = index;
  for (std::size_t g = 0; g < c.grids.size(); ++g) {
    const Grid& grid = c.grids[g];
    const std::uint64_t per_scene = grid.size();
    const std::uint64_t here = per_scene * c.scenes.size();
    if (j >= here) {
      j -= here;
      continue;
    }
    Point p;
    p.index = index;
    p.grid = g;
    p.scene = static_cast<std::size_t>(j / per_scene);
    std::uint64_t k = j % per_scene;
    p.values.resize(grid.axes.size());
    if (grid.combine == Combine::zip) {
      for (std::size_t a = 0; a < grid.axes.size(); ++a) p.values[a] = {&grid.axes[a], grid.axes[a].value(k)};
    } else {
      for (std::size_t a = grid.axes.size(); a-- > 0;) {  // last axis fastest
        const std::uint64_t n = grid.axes[a].size();
        p.values[a] = {&grid.axes[a], grid.axes[a].value(k % n)};
        k /= n;
      }
    }
    return p;
  }
  throw std::out_of_range("point index " + std::to_string(index) + " out of range (campaign has " +
                          std::to_string(c.size()) + " points)");
}

}  // namespace asperity
