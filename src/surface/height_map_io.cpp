#include "surface/height_map_io.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"

namespace asperity {

namespace fs = std::filesystem;
using io::MapView;
using io::Source;

std::string pixel_size_problem(double pixel_m) {
  if (pixel_m >= kMinPixel_m && pixel_m <= kMaxPixel_m) return "";
  return "pixel size must be in [" + io::format_double(kMinPixel_m) + ", " + io::format_double(kMaxPixel_m) +
         "] m, got " + io::format_double(pixel_m);
}

std::optional<HeightRangeProblem> height_range_problem(const HeightMap& map) {
  if (map.h_m.empty()) return std::nullopt;
  const auto [lo, hi] = std::minmax_element(map.h_m.begin(), map.h_m.end());
  const double side = map.pixel_m * static_cast<double>(map.n);
  if (*hi - *lo <= side) return std::nullopt;  // (an overflow to inf is refused too)
  std::vector<double> sorted = map.h_m;
  auto mid = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
  std::nth_element(sorted.begin(), mid, sorted.end());
  const double median = *mid;
  const auto far = median - *lo > *hi - median ? lo : hi;  // (differences of finite doubles: no NaN)
  HeightRangeProblem p;
  p.index = static_cast<std::size_t>(far - map.h_m.begin());
  p.message = "height " + io::format_double(*far) + " m: the heights span " + io::format_short(*hi - *lo) +
              " m (from " + io::format_short(*lo) + " to " + io::format_short(*hi) +
              "), more than the map's side n x pixel_m = " + io::format_short(side) +
              " m; a contact solve needs heights within the map's size";
  return p;
}

HeightMap read_height_map_csv(const fs::path& csv, const std::string& display, double pixel_m) {
  if (const std::string why = pixel_size_problem(pixel_m); !why.empty()) throw io::InputError(display, 0, "", why);
  const io::CsvMatrix m = io::read_numeric_matrix_csv(csv, display, "h_m", kMaxHeightMapSide, kMaxHeightMapSide);
  if (m.rows != m.columns)
    throw io::InputError(display, m.first_line, "h_m",
                         "height map is " + std::to_string(m.rows) + " rows of " + std::to_string(m.columns) +
                             " values; it must be square (n rows of n heights)");
  if (m.rows < 2) throw io::InputError(display, m.first_line, "h_m", "height map must be at least 2 x 2");
  HeightMap map;
  map.n = m.rows;
  map.pixel_m = pixel_m;
  map.h_m = m.values;
  if (const auto p = height_range_problem(map))
    throw io::InputError(display, m.lines[p->index / map.n], "h_m", p->message, static_cast<int>(p->index % map.n) + 1);
  return map;
}

HeightMap read_height_map_binary(const fs::path& header_yaml, const std::string& display) {
  const YAML::Node root = io::load_yaml_file(header_yaml, display);
  const MapView v(Source{display, nullptr}, root, "", {"n", "pixel_m", "data", "format"}, 1);
  if (const auto f = v.find("format")) v.enumeration<int>(*f, "format", {{"float64_le", 0}});
  const YAML::Node nn = v.require("n");
  const int n_int = v.integer(nn, "n");
  if (n_int < 2 || static_cast<std::size_t>(n_int) > kMaxHeightMapSide)
    v.fail_at(nn, "n", "must be in [2, " + std::to_string(kMaxHeightMapSide) + "], got " + std::to_string(n_int));
  const auto n = static_cast<std::size_t>(n_int);
  const YAML::Node pn = v.require("pixel_m");
  const double pixel_m = v.number(pn, "pixel_m", "m");
  if (const std::string why = pixel_size_problem(pixel_m); !why.empty()) v.fail_at(pn, "pixel_m", why);

  const YAML::Node dn = v.require("data");
  const std::string rel = v.string(dn, "data");
  if (io::trim(rel).empty()) v.fail_at(dn, "data", "empty path (expected the float64 height file)");
  const fs::path data = header_yaml.parent_path() / fs::path(rel);
  const std::uintmax_t bytes = static_cast<std::uintmax_t>(n) * n * sizeof(double);
  // Checked by path before opening (a FIFO is never opened), at the line that names the file.
  if (std::string why = io::input_file_problem(data, bytes); !why.empty()) {
    std::error_code ec;
    if (why != "file not found" && fs::is_regular_file(data, ec)) why = "is larger than expected";
    v.fail_at(dn, "data",
              "height file " + why + ": " + io::input_path(data) + " (expected n^2 x 8 = " + std::to_string(bytes) +
                  " bytes of float64 little-endian)");
  }
  const std::string raw = io::read_input_file(data, io::input_path(data), bytes);
  if (raw.size() != bytes)
    v.fail_at(dn, "data",
              "height file " + io::input_path(data) + " has " + std::to_string(raw.size()) +
                  " bytes, expected n^2 x 8 = " + std::to_string(bytes) + " (float64 little-endian)");
  HeightMap map;
  map.n = n;
  map.pixel_m = pixel_m;
  map.h_m.resize(n * n);
  for (std::size_t k = 0; k < n * n; ++k) {
    // Assembled byte by byte: little-endian whatever the machine's order, no aligned access.
    std::uint64_t u = 0;
    for (int b = 7; b >= 0; --b) u = (u << 8) | static_cast<unsigned char>(raw[k * 8 + static_cast<std::size_t>(b)]);
    const double h = std::bit_cast<double>(u);
    if (!std::isfinite(h))
      v.fail_at(dn, "data",
                "height at row " + std::to_string(k / n + 1) + ", column " + std::to_string(k % n + 1) + " of " +
                    io::input_path(data) + " is " + (std::isnan(h) ? "NaN" : "infinite") +
                    "; every height must be finite");
    map.h_m[k] = h;
  }
  if (const auto p = height_range_problem(map))
    v.fail_at(dn, "data",
              "row " + std::to_string(p->index / n + 1) + ", column " + std::to_string(p->index % n + 1) + " of " +
                  io::input_path(data) + ": " + p->message);
  return map;
}

void write_height_map_csv(const fs::path& csv, const HeightMap& map) {
  std::string s = "# height map: " + std::to_string(map.n) + " x " + std::to_string(map.n) +
                  " heights in metres, pixel_m = " + io::csv_number(map.pixel_m) + "\n";
  for (std::size_t i = 0; i < map.n; ++i) {
    for (std::size_t j = 0; j < map.n; ++j) {
      if (j) s += ',';
      s += io::csv_number(map.h_m[i * map.n + j]);
    }
    s += '\n';
  }
  io::write_file_atomically(csv, s, io::Durability::unsynced);
}

void write_height_map_binary(const fs::path& header_yaml, const std::string& data_name, const HeightMap& map) {
  std::string raw(map.h_m.size() * 8, '\0');
  for (std::size_t k = 0; k < map.h_m.size(); ++k) {
    const auto u = std::bit_cast<std::uint64_t>(map.h_m[k]);
    for (std::size_t b = 0; b < 8; ++b) raw[k * 8 + b] = static_cast<char>((u >> (8 * b)) & 0xff);
  }
  io::write_file_atomically(header_yaml.parent_path() / data_name, raw, io::Durability::unsynced);
  io::write_file_atomically(header_yaml,
                            "n: " + std::to_string(map.n) + "\npixel_m: " + io::format_double(map.pixel_m) +
                                "\ndata: " + io::yaml_quoted(data_name) + "\nformat: float64_le\n",
                            io::Durability::unsynced);
}

}  // namespace asperity
