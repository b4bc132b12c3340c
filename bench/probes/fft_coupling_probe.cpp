// Probe (ASPERITY_PROBES builds it): the precorrected-FFT product of the coupling
// (solve/interacting/fft_coupling.hpp) beside the dense product over the stored triangle of C, the
// way the dense solver's passes read it, on `bench interacting`'s populations (the stand-in
// P4.00N's areas repeated to N, placed in a disc of radius 4.5 mm · sqrt(N / 1201)). Prints CSV:
// set-up and per-product times (median of R products, one thread), the exact pairs, the padded
// grid, and the error max_i |ỹ_i − y_i| / max_i |y_i| against the dense product (N ≤ dense_max).
// Build against a Release build in build/ and run from the repository root:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build fft_coupling_probe
//   OMP_NUM_THREADS=1 build/fft_coupling_probe 1200 5000 20000
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "physics/elastic_interaction.hpp"
#include "probe_population.hpp"
#include "solve/interacting/fft_coupling.hpp"
using namespace asperity;

int main(int argc, char** argv) {
  std::printf(
      "N,order,cell_per_spacing,near_cells,setup_s,product_ms,dense_product_ms,speedup,near_pairs_per_junction,grid_"
      "points,error\n");
  for (int k = 1; k < argc; ++k) {
    const std::size_t N = std::atoi(argv[k]);
    const ProbePopulation p = probe_population(N);
    const std::vector<double>& a = p.radius_m;
    const double E = p.E_pa, nu = p.nu;
    std::vector<double> f(N);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0.2, 1.0);
    for (auto& v : f) v = u(rng);
    // Dense: the strict lower triangle, row-major packed, one pass reading each entry once.
    std::vector<double> L(N * (N - 1) / 2), exact(N, 0.0);
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = 0; j < i; ++j)
        L[i * (i - 1) / 2 + j] = disc_compliance(p.x_m[i] - p.x_m[j], p.y_m[i] - p.y_m[j], a[i], a[j], E, nu);
    const auto dense = [&](std::vector<double>& y) {
      std::fill(y.begin(), y.end(), 0.0);
      for (std::size_t i = 1; i < N; ++i) {
        const double* row = L.data() + i * (i - 1) / 2;
        const double fi = f[i];
        double t = 0;
#pragma omp simd reduction(+ : t)
        for (std::size_t j = 0; j < i; ++j) t += row[j] * f[j], y[j] += row[j] * fi;
        y[i] += t;
      }
    };
    const int R = N >= 20000 ? 5 : 20;
    std::vector<double> times;
    for (int r = 0; r < std::max(3, R / 4); ++r) {
      const auto t0 = ProbeClock::now();
      dense(exact);
      times.push_back(seconds_since(t0));
    }
    std::sort(times.begin(), times.end());
    const double dense_s = times[times.size() / 2];
    double ymax = 0;
    for (double v : exact) ymax = std::max(ymax, std::abs(v));
    struct Knob {
      int order;
      double cell, near;
    };
    for (const Knob kn : {Knob{6, 1.0, 8}, Knob{6, 0.5, 16}, Knob{8, 0.5, 12}, Knob{8, 0.5, 16}, Knob{8, 0.35, 11.4},
                          Knob{8, 0.35, 17.1}}) {
      FftCouplingSettings s{kn.order, kn.near, kn.cell};
      auto t0 = ProbeClock::now();
      const FftCoupling c(p.x_m, p.y_m, a, E, nu, TractionWeighting::uniform, s);
      const double setup = seconds_since(t0);
      std::vector<double> y(N);
      times.clear();
      for (int r = 0; r < R; ++r) {
        t0 = ProbeClock::now();
        c.apply(f.data(), y.data());
        times.push_back(seconds_since(t0));
      }
      std::sort(times.begin(), times.end());
      double e = 0;
      for (std::size_t i = 0; i < N; ++i) e = std::max(e, std::abs(y[i] - exact[i]));
      const double prod = times[times.size() / 2];
      std::printf("%zu,%d,%.2f,%.1f,%.3f,%.3f,%.3f,%.1f,%.1f,%zu,%.2e\n", N, kn.order, kn.cell, kn.near, setup,
                  1e3 * prod, 1e3 * dense_s, dense_s / prod, 2.0 * c.near_pairs() / N, c.grid_points(), e / ymax);
      std::fflush(stdout);
    }
  }
}
