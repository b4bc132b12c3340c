// surface/height_map_io.hpp: measured height maps (CSV matrix, float64 LE with a YAML header)
// read back bit for bit, and bad files refused naming file, line and column or key.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "io/input_error.hpp"
#include "support_files.hpp"
#include "surface/height_map_io.hpp"

using namespace asperity;
namespace fs = std::filesystem;
using asperity::testing::fresh_dir;
using asperity::testing::write_text;

namespace {

// Heights that exercise the shortest round-trip text: signs, tiny and huge exponents, subnormals
// (spanning up to 2e-3 m, within the map's side as a reader requires).
HeightMap awkward_map(std::size_t n) {
  HeightMap m;
  m.n = n;
  m.pixel_m = 1.0 / 3.0 * 1e-2;
  for (std::size_t k = 0; k < n * n; ++k) {
    const double x = std::sin(1.7 * static_cast<double>(k) + 0.3) * std::pow(10.0, static_cast<double>(k % 7) - 9);
    m.h_m.push_back(k == 5 ? std::numeric_limits<double>::denorm_min() : k == 6 ? -0.0 : x);
  }
  return m;
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("height maps: CSV and float64 files round-trip bit for bit", "[surface][height_map_io]") {
  const fs::path d = fresh_dir("asperity-height-map-io");
  const HeightMap m = awkward_map(9);
  write_height_map_csv(d / "map.csv", m);
  const HeightMap c = read_height_map_csv(d / "map.csv", "map.csv", m.pixel_m);
  CHECK(c.n == m.n);
  CHECK(c.pixel_m == m.pixel_m);
  REQUIRE(c.h_m.size() == m.h_m.size());
  for (std::size_t k = 0; k < m.h_m.size(); ++k) CHECK(std::signbit(c.h_m[k]) == std::signbit(m.h_m[k]));
  CHECK(c.h_m == m.h_m);

  write_height_map_binary(d / "map.yaml", "map.f64", m);
  CHECK(fs::file_size(d / "map.f64") == 81 * 8);
  const HeightMap b = read_height_map_binary(d / "map.yaml", "map.yaml");
  CHECK(b.n == m.n);
  CHECK(b.pixel_m == m.pixel_m);
  CHECK(b.h_m == m.h_m);
  // Little-endian on disk whatever the machine: 1.0 is 00 .. f0 3f.
  HeightMap one{2, 1e-6, {1.0, 0, 0, 0}};
  write_height_map_binary(d / "one.yaml", "one.f64", one);
  const std::string raw = asperity::testing::slurp(d / "one.f64");
  CHECK(static_cast<unsigned char>(raw[6]) == 0xf0);
  CHECK(static_cast<unsigned char>(raw[7]) == 0x3f);
  fs::remove_all(d);
}

TEST_CASE("height maps: bad CSV maps are refused at their line", "[surface][height_map_io]") {
  const fs::path d = fresh_dir("asperity-height-map-bad-csv");
  const auto csv_error = [&](const std::string& text) {
    write_text(d / "h.csv", text);
    return error_of([&] { read_height_map_csv(d / "h.csv", "h.csv", 1e-6); });
  };
  CHECK(csv_error("# map\n0,1e-6\n2e-6,NaN\n") == "h.csv:3:2: h_m: must be a finite number, got 'NaN'");
  CHECK(csv_error("0,1,2\n3,4,5\n") ==
        "h.csv:1: h_m: height map is 2 rows of 3 values; it must be square (n rows of n heights)");
  CHECK(csv_error("0,1\n2\n") == "h.csv:2:2: h_m: expected 2 values (as in the first row, line 1), got 1");
  CHECK(csv_error("5\n") == "h.csv:1: h_m: height map must be at least 2 x 2");
  // A row wider than the cap is refused before any row is stored (8193 zeros: 16 kB).
  std::string wide = "0";
  for (std::size_t j = 1; j <= kMaxHeightMapSide; ++j) wide += ",0";
  CHECK(csv_error(wide + "\n") == "h.csv:1:8193: h_m: row of 8193 values, more than the 8192 allowed");
  // Not a regular file: a folder and a FIFO (never opened, so never waited on).
  fs::create_directories(d / "dir.csv");
  CHECK(error_of([&] { read_height_map_csv(d / "dir.csv", "dir.csv", 1e-6); }) ==
        "dir.csv: is a directory, not a file");
  REQUIRE(::mkfifo((d / "fifo.csv").c_str(), 0600) == 0);
  CHECK(error_of([&] { read_height_map_csv(d / "fifo.csv", "fifo.csv", 1e-6); }) ==
        "fifo.csv: is a FIFO (named pipe), not a regular file");
  fs::remove_all(d);
}

TEST_CASE("height maps: bad float64 maps and headers are refused at the header's key", "[surface][height_map_io]") {
  const fs::path d = fresh_dir("asperity-height-map-bad-bin");
  write_height_map_binary(d / "ok.yaml", "ok.f64", awkward_map(4));
  const auto header_error = [&](const std::string& header) {
    write_text(d / "h.yaml", header);
    return error_of([&] { read_height_map_binary(d / "h.yaml", "h.yaml"); });
  };
  // n is capped before anything is allocated or read.
  CHECK(header_error("n: 100000\npixel_m: 1e-6\ndata: ok.f64\n") == "h.yaml:1: n: must be in [2, 8192], got 100000");
  CHECK(header_error("n: 5\npixel_m: 1e-6\ndata: ok.f64\n")
            .rfind("h.yaml:3: data: height file " + (d / "ok.f64").string() + " has 128 bytes, expected n^2 x 8 = 200",
                   0) == 0);
  CHECK(header_error("n: 3\npixel_m: 1e-6\ndata: ok.f64\n")
            .rfind("h.yaml:3: data: height file is larger than expected: ", 0) == 0);
  CHECK(header_error("n: 4\npixel_m: 0\ndata: ok.f64\n") ==
        "h.yaml:2: pixel_m: pixel size must be in [1e-10, 1] m, got 0");
  CHECK(header_error("n: 4\npixel_m: 1e-200\ndata: ok.f64\n") ==
        "h.yaml:2: pixel_m: pixel size must be in [1e-10, 1] m, got 1e-200");
  CHECK(
      header_error("n: 4\npixel_m: 1e-6\ndata: missing.f64\n").rfind("h.yaml:3: data: height file file not found", 0) ==
      0);
  CHECK(header_error("n: 4\npixel_m: 1e-6\ndata: ok.f64\nformat: float32\n")
            .rfind("h.yaml:4: format: unknown value 'float32'", 0) == 0);
  CHECK(header_error("n: 4\npixel_m: 1e-6\n") == "h.yaml:1: data: missing required key");
  HeightMap nan_map = awkward_map(4);
  nan_map.h_m[6] = std::numeric_limits<double>::quiet_NaN();  // row 2, column 3
  write_height_map_binary(d / "nan.yaml", "nan.f64", nan_map);
  CHECK(error_of([&] { read_height_map_binary(d / "nan.yaml", "nan.yaml"); }) ==
        "nan.yaml:3: data: height at row 2, column 3 of " + (d / "nan.f64").string() +
            " is NaN; every height must be finite");
  REQUIRE(::mkfifo((d / "fifo.f64").c_str(), 0600) == 0);
  CHECK(header_error("n: 4\npixel_m: 1e-6\ndata: fifo.f64\n")
            .rfind("h.yaml:3: data: height file is a FIFO (named pipe), not a regular file", 0) == 0);
  fs::remove_all(d);
}
