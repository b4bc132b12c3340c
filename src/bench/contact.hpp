#pragma once
// `asperity bench contact`: the FFT boundary-element normal contact (surface/normal_contact.hpp)
// of a sphere carrying a self-affine surface, at several grid sizes: wall time, CG iterations,
// time per iteration beside the time of two FFT pairs (FFTW's 2-D r2c + c2r on the padded grid, the
// work of one Polonsky–Keer iteration done plainly), timed in the same run with the same threads,
// and peak memory; beside it the tangential solve on the same contact map
// (surface/tangential_contact.hpp: Coulomb μ 0.5, from rest to half the full-sliding displacement).
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <vector>

#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"
#include "surface/tangential_contact.hpp"

namespace asperity {

struct ContactBenchRow {
  std::size_t n = 0;  // pixels per side (the padded grid is 2n)
  int threads = 1;
  int iterations = 0;         // on the n grid
  int coarse_iterations = 0;  // on the coarser grids of the coarse-to-fine start
  int convolutions = 0;       // FFT pairs on the n grid (fewer than 2 per iteration: see normal_contact.cpp)
  bool converged = false;
  double wall_s = 0;           // the whole solve (kernel, coarse grids, iterations)
  double per_iteration_s = 0;  // wall_s / iterations
  double fft_pair_s = 0;       // one forward + inverse FFT on 2n × 2n, median of several
  double area_m2 = 0;
  // The tangential solve (kernel, one solve from q = 0) and its iterations and FFT pairs.
  double tangential_wall_s = 0;
  int tangential_iterations = 0;
  int tangential_convolutions = 0;
  bool tangential_converged = false;
  long max_rss_kB = 0;  // of the process after this size (sizes in increasing order)
};

struct ContactBenchOptions {
  std::vector<std::size_t> sizes{256, 512, 1024};
  double tolerance = 1e-8;
  int threads = 1;
  std::ostream* log = nullptr;
};

// The workload at n pixels: a PDMS-like sphere (R 9.5 mm) carrying a self-affine surface on a 4 mm
// box, and its settings (E* 2.13 MPa, 4 N, the tolerance given); the tests solve the same one.
HeightMap contact_bench_surface(std::size_t n);
NormalContactSettings contact_bench_settings(double tolerance);
// The tangential solve's settings for that workload (E = E*(1 − ν²), ν 0.5, the tolerance given).
TangentialContactSettings tangential_bench_settings(double tolerance);

std::vector<ContactBenchRow> run_contact_bench(const ContactBenchOptions& opt);
void write_contact_bench(const std::filesystem::path& dir,
                         const std::vector<ContactBenchRow>& rows);  // DIR/contact.csv

}  // namespace asperity
