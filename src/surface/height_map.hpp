#pragma once
// A topography: heights on a square grid of n × n pixels (row-major, h[i * n + j] at x = j·pixel,
// y = i·pixel), in metres. Larger h is closer to the counter-surface (a summit touches first).
#include <cstddef>
#include <vector>

namespace asperity {

struct HeightMap {
  std::size_t n = 0;
  double pixel_m = 0;       // side of one pixel
  std::vector<double> h_m;  // n * n heights
  double length_m() const { return pixel_m * static_cast<double>(n); }
};

// Adds a sphere of radius R (paraboloid cap, z = −r²/2R, r from the grid's centre) to `map`.
void add_sphere(HeightMap& map, double radius_m);

// The rms height and the rms slope (central differences, periodic) of a map.
double rms_height(const HeightMap& map);
double rms_slope(const HeightMap& map);

}  // namespace asperity
