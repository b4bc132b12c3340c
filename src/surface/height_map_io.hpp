#pragma once
// Measured height maps, read as untrusted input: every problem is an InputError naming the file,
// the line (and CSV column or YAML key) on one line; sizes are capped before anything is
// allocated for them; NaN and infinities, non-square maps and files that are not regular files
// (a FIFO, a device, a folder) are refused.
//   CSV: n rows of n heights in metres (io/csv.hpp's numeric matrix: '#' comments, no header);
//        the pixel size comes from whoever names the file (a recipe).
//   binary: a YAML header {n, pixel_m, data, format: float64_le} next to (or naming, relative
//        to its own folder) a file of exactly n² float64 little-endian heights, row-major
//        (h[i·n + j] at x = j·pixel, y = i·pixel, as HeightMap stores them).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "surface/height_map.hpp"

namespace asperity {

// The largest side accepted, far above any profilometer scan a contact solve can afford
// (8192² float64 is 512 MiB); checked before the heights are read.
inline constexpr std::size_t kMaxHeightMapSide = 8192;

// Pixel sizes a contact solve accepts: from 1e-10 m (an atom; one pixel is then the smallest
// junction, 1e-20 m^2) to 1 m (one pixel the largest, 1 m^2; scene/csv.hpp's junction rule).
// Outside, the solve's numbers leave the range of double or its contact means nothing.
inline constexpr double kMinPixel_m = 1e-10, kMaxPixel_m = 1.0;
std::string pixel_size_problem(double pixel_m);  // "" when allowed, else the message

// The heights of a map must span (highest - lowest) no more than the map's side, n x pixel: a
// wider span is a spike or a pit no contact solve resolves (1e308 overflows it). The row-major
// index of the height farthest from the median, and the message; nullopt when allowed.
struct HeightRangeProblem {
  std::size_t index = 0;
  std::string message;
};
std::optional<HeightRangeProblem> height_range_problem(const HeightMap& map);

HeightMap read_height_map_csv(const std::filesystem::path& csv, const std::string& display, double pixel_m);
HeightMap read_height_map_binary(const std::filesystem::path& header_yaml, const std::string& display);

// Writers for the same formats (shortest round-trip numbers / raw float64 LE, so reading back
// gives the map bit for bit), written atomically. The binary writer puts `data_name` next to
// the header. std::runtime_error when a file cannot be written.
void write_height_map_csv(const std::filesystem::path& csv, const HeightMap& map);
void write_height_map_binary(const std::filesystem::path& header_yaml, const std::string& data_name,
                             const HeightMap& map);

}  // namespace asperity
