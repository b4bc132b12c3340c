// surface/normal_contact.cpp's speed-ups (issue 23): the coarse-to-fine start, the pruned padded
// FFTs, the skipped convolutions and the threads must not change the answer beyond the tolerance.
// Checked against a uniform start, against displacements summed directly from Love's rectangle,
// and bit for bit across runs and thread counts.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <vector>

#include "bench/contact.hpp"
#include "surface/height_map.hpp"
#include "surface/normal_contact.hpp"
#include "surface/self_affine.hpp"

using namespace asperity;

namespace {

// The bench's workload (src/bench/contact.cpp) at n pixels: a rough sphere, 4 N, E* 2.13 MPa.
HeightMap rough_sphere(std::size_t n) { return contact_bench_surface(n); }
NormalContactSettings settings(double tolerance) { return contact_bench_settings(tolerance); }

}  // namespace

TEST_CASE("contact: the coarse-to-fine start converges to the contact of a uniform start", "[surface][contact]") {
  const HeightMap m = rough_sphere(256);
  NormalContactSettings c = settings(1e-10);
  const NormalContact warm = solve_normal_contact(m, c);
  c.coarse_start = false;
  const NormalContact cold = solve_normal_contact(m, c);
  REQUIRE(warm.converged);
  REQUIRE(cold.converged);
  double dp = 0, total = 0;
  std::size_t flipped = 0;
  for (std::size_t k = 0; k < m.h_m.size(); ++k) {
    dp += std::abs(warm.pressure_Pa[k] - cold.pressure_Pa[k]), total += cold.pressure_Pa[k];
    flipped += (warm.pressure_Pa[k] > 0) != (cold.pressure_Pa[k] > 0);
  }
  INFO("iterations " << warm.iterations << " (+ " << warm.coarse_iterations << " coarse) vs " << cold.iterations
                     << "; sum|dp|/sum p " << dp / total << ", pixels flipped " << flipped << ", approach "
                     << warm.approach_m / cold.approach_m - 1);
  CHECK(warm.coarse_iterations > 0);  // the start was taken
  // Measured (tolerance 1e-10): 97 iterations (+ 71 coarse) vs 114, sum|dp|/sum p 1.3e-10, no pixel
  // flipped, approach 6e-13.
  CHECK(dp / total < 1e-9);
  CHECK(flipped == 0);
  CHECK(std::abs(warm.approach_m / cold.approach_m - 1) < 5e-12);
}

TEST_CASE("contact: the solved gaps match displacements summed directly from Love's rectangle", "[surface][contact]") {
  // 128² (a coarse start from 64²) at 0.5 N (Hertz radius 1.2 mm on the 4 mm map): the
  // displacement at every pixel summed over the loaded pixels with Love's closed form, no FFT; the
  // solver's gap must equal it, vanish on the contact and be positive off it.
  const std::size_t n = 128;
  const HeightMap m = rough_sphere(n);
  NormalContactSettings s = settings(1e-10);
  s.load_N = 0.5;
  const NormalContact c = solve_normal_contact(m, s);
  REQUIRE(c.converged);
  REQUIRE(c.coarse_iterations > 0);
  const double top = *std::max_element(m.h_m.begin(), m.h_m.end()), half = 0.5 * m.pixel_m;
  std::vector<double> love(n * n);  // by |offset| (Love's rectangle is even in both)
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j)
      love[i * n + j] =
          love_rectangle(static_cast<double>(j) * m.pixel_m, static_cast<double>(i) * m.pixel_m, half, half);
  std::vector<std::size_t> loaded;
  for (std::size_t k = 0; k < n * n; ++k)
    if (c.pressure_Pa[k] > 0) loaded.push_back(k);
  auto dist = [](std::size_t a, std::size_t b) { return a > b ? a - b : b - a; };
  double worst_gap = 0, worst_on = 0, most_negative = 0, scale = 0;
  for (std::size_t k = 0; k < n * n; ++k) {
    double u = 0;
    for (const std::size_t l : loaded) u += c.pressure_Pa[l] * love[dist(k / n, l / n) * n + dist(k % n, l % n)];
    u /= s.E_star_Pa;
    const double gap = u + (top - m.h_m[k]) - c.approach_m;
    scale = std::max(scale, std::abs(gap));
    worst_gap = std::max(worst_gap, std::abs(std::max(0.0, gap) - c.gap_m[k]));
    if (c.pressure_Pa[k] > 0)
      worst_on = std::max(worst_on, std::abs(gap));
    else
      most_negative = std::min(most_negative, gap);
  }
  INFO(loaded.size() << " pixels in contact; largest gap " << scale << " m; |gap - direct| " << worst_gap
                     << "; |gap| on the contact " << worst_on << "; most negative gap off it " << most_negative);
  // Measured: 4520 pixels in contact, largest gap 2.9e-4 m; |gap - direct| 1.1e-18 m, |gap| on the
  // contact 2.9e-15 m (1e-11 of the largest gap), none negative off it.
  CHECK(worst_gap < 1e-13 * scale);
  CHECK(worst_on < 5e-11 * scale);
  CHECK(most_negative > -5e-11 * scale);
}

TEST_CASE("contact: two runs, and one or two threads, give the same bytes", "[surface][contact]") {
  // 512²: the loops over pixels are split among threads from 2^18 points on, so this size takes
  // every threaded path (FFTW's threads, the block sums); a loose tolerance and a uniform start
  // keep the test short.
  const HeightMap m = rough_sphere(512);
  NormalContactSettings c = settings(1e-2);
  c.coarse_start = false;
  const NormalContact a = solve_normal_contact(m, c), b = solve_normal_contact(m, c);
  c.threads = 2;
  const NormalContact t = solve_normal_contact(m, c);
  REQUIRE(a.converged);
  INFO(a.iterations << " iterations, " << a.coarse_iterations << " coarse");
  const std::size_t bytes = a.pressure_Pa.size() * sizeof(double);
  CHECK(std::memcmp(a.pressure_Pa.data(), b.pressure_Pa.data(), bytes) == 0);
  CHECK(std::memcmp(a.pressure_Pa.data(), t.pressure_Pa.data(), bytes) == 0);
  CHECK(std::memcmp(a.gap_m.data(), t.gap_m.data(), bytes) == 0);
  CHECK(a.iterations == t.iterations);
}
