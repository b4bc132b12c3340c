#include "surface/height_map.hpp"

#include <cmath>

namespace asperity {

void add_sphere(HeightMap& map, double radius_m) {
  const double c = 0.5 * static_cast<double>(map.n - 1);
  for (std::size_t i = 0; i < map.n; ++i)
    for (std::size_t j = 0; j < map.n; ++j) {
      const double x = (static_cast<double>(j) - c) * map.pixel_m, y = (static_cast<double>(i) - c) * map.pixel_m;
      map.h_m[i * map.n + j] -= (x * x + y * y) / (2 * radius_m);
    }
}

double rms_height(const HeightMap& map) {
  double mean = 0, sq = 0;
  for (const double h : map.h_m) mean += h;
  mean /= static_cast<double>(map.h_m.size());
  for (const double h : map.h_m) sq += (h - mean) * (h - mean);
  return std::sqrt(sq / static_cast<double>(map.h_m.size()));
}

double rms_slope(const HeightMap& map) {
  const std::size_t n = map.n;
  double sq = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const double dx = (map.h_m[i * n + (j + 1) % n] - map.h_m[i * n + (j + n - 1) % n]) / (2 * map.pixel_m);
      const double dy = (map.h_m[((i + 1) % n) * n + j] - map.h_m[((i + n - 1) % n) * n + j]) / (2 * map.pixel_m);
      sq += dx * dx + dy * dy;
    }
  return std::sqrt(sq / static_cast<double>(n * n));
}

}  // namespace asperity
