#pragma once
// Shared by the libFuzzer targets: each input is written to a file in a per-process directory
// (the loaders read files, as users' inputs are files) and loaded; InputError is the expected
// answer to bad input, anything else escaping (another exception, a crash, a sanitizer report)
// is a bug.
//
// The work dir is <tmp>/asperity-fuzz-<pid>/a/b, and holds valid files to refer to: junctions.csv,
// measured.csv, experiment.yaml and base_scene.yaml (a small scene whose experiment has a
// measured curve). The shipped scenes/ and data/ are linked at <pid>/ and <pid>/a/, so the seeds'
// relative paths (sweeps/, fits/: ../scenes/...; tests/bad_inputs/: ../../scenes/...) resolve
// and valid-looking campaigns and fits reach the deeper checks.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace asperity::fuzz {

inline const std::filesystem::path& work_dir() {
  static const std::filesystem::path dir =
      [] {
        namespace fs = std::filesystem;
        const auto root = fs::temp_directory_path() / ("asperity-fuzz-" + std::to_string(::getpid()));
        const auto d = root / "a" / "b";
        fs::create_directories(d);
#ifdef ASPERITY_SOURCE_DIR
        const fs::path src(ASPERITY_SOURCE_DIR);
        for (const auto& at : {root, root / "a"})
          for (const char* sub : {"scenes", "data"}) {
            std::error_code ec;
            fs::create_directory_symlink(src / sub, at / sub, ec);
          }
#endif
        std::ofstream(d / "junctions.csv") << "area_m2\n1e-8\n2e-8\n3e-8\n";
        std::ofstream(d / "measured.csv") << "Q_N,A_m2\n0,6e-8\n0.01,5.9e-8\n0.02,5.7e-8\n";
        std::ofstream(d / "experiment.yaml")
            << "name: f\nmass: 0.1\nk_L: 9200\nv: 1e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 230000\n"
               "junctions: junctions.csv\nmeasured: measured.csv\n";
        std::ofstream(d / "base_scene.yaml") << "experiment: experiment.yaml\nmodel: {eta: 100, alpha_b: 7.25e-16}\n";
        return d;
      }();
  return dir;
}

inline std::filesystem::path write_input(const char* name, const std::uint8_t* data, std::size_t size) {
  const auto p = work_dir() / name;
  std::ofstream(p, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return p;
}

}  // namespace asperity::fuzz
