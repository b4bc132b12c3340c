#pragma once
// Shared by the libFuzzer targets: each input is written to a file in a per-process directory
// (the loaders read files, as users' inputs are files) and loaded; InputError is the expected
// answer to bad input, anything else escaping (another exception, a crash, a sanitizer report)
// is a bug.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace asperity::fuzz {

inline const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("asperity-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    // A valid junction list and experiment for inputs that refer to them.
    std::ofstream(d / "junctions.csv") << "area_m2\n1e-8\n2e-8\n3e-8\n";
    std::ofstream(d / "experiment.yaml")
        << "name: f\nmass: 0.1\nk_L: 9200\nv: 1e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 230000\njunctions: junctions.csv\n";
    return d;
  }();
  return dir;
}

inline std::filesystem::path write_input(const char* name, const std::uint8_t* data, std::size_t size) {
  const auto p = work_dir() / name;
  std::ofstream(p, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data),
                                                             static_cast<std::streamsize>(size));
  return p;
}

}  // namespace asperity::fuzz
