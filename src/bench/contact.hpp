#pragma once
// `asperity bench contact`: the FFT boundary-element normal contact (surface/normal_contact.hpp)
// of a sphere carrying a self-affine surface, at several grid sizes: wall time, CG iterations,
// time per iteration beside the time of the two FFT pairs (forward + inverse on the padded grid)
// an iteration needs, timed in the same run, and peak memory.
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <vector>

namespace asperity {

struct ContactBenchRow {
  std::size_t n = 0;               // pixels per side (the padded grid is 2n)
  int iterations = 0;
  bool converged = false;
  double wall_s = 0;               // the whole solve
  double per_iteration_s = 0;
  double fft_pair_s = 0;           // one forward + inverse FFT on 2n × 2n, median of several
  double area_m2 = 0;
  long max_rss_kB = 0;             // of the process after this size (sizes in increasing order)
};

struct ContactBenchOptions {
  std::vector<std::size_t> sizes{256, 512, 1024};
  double tolerance = 1e-8;
  std::ostream* log = nullptr;
};

std::vector<ContactBenchRow> run_contact_bench(const ContactBenchOptions& opt);
void write_contact_bench(const std::filesystem::path& dir, const std::vector<ContactBenchRow>& rows);  // DIR/contact.csv

}  // namespace asperity
