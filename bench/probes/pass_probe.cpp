// Probe (ASPERITY_PROBES builds it): the floor of the dense exact solver at large N. One
// chord pass reads the pinned set's triangle of G once, in its single-precision copy from N =
// 2,048 on: this times one such pass over a full packed float triangle (synthetic entries; the
// time depends only on the bytes read) with the solver's own product kernel (the CPU's fastest
// form), the rows split in blocks of equal entries over the OpenMP threads, best of 5.
// At N = 20,000 issue 26's 20 minutes leave 60 ms per slip (about N slips to the first peak).
// Build against a Release build in build/ and run from the repository root:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build pass_probe
//   OMP_NUM_THREADS=2 build/pass_probe 5000 20000
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "solve/interacting/pinned_compliance.hpp"
#include "solve/interacting/pinned_kernels.hpp"
using namespace asperity;

int main(int argc, char** argv) {
  const ProductKernel kernel = product_kernels().back();
  const int threads = omp_get_max_threads();
  std::printf("N,threads,kernel,entries,pass_ms,ns_per_entry,GB_per_s\n");
  for (int k = 1; k < argc; ++k) {
    const std::size_t N = std::atoi(argv[k]), total = N * (N + 1) / 2;
    std::vector<float> S(total);
    for (std::size_t e = 0; e < total; ++e) S[e] = 1e-3f * static_cast<float>((e * 2654435761u) % 1000);
    std::vector<double> w1(N, 1.0), w2(N, 0.5);
    std::vector<std::size_t> cut(threads + 1, N);
    cut[0] = 0;
    for (int t = 1; t < threads; ++t) {
      std::size_t r = 0;
      while (packed_row(r, N) < total * t / threads) ++r;
      cut[t] = r;
    }
    std::vector<std::vector<double>> p1(threads, std::vector<double>(N)), p2(threads, std::vector<double>(N));
    double best = 1e30;
    for (int rep = 0; rep < 5; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel
      {
        const int t = omp_get_thread_num();
        std::fill(p1[t].begin(), p1[t].end(), 0.0);
        std::fill(p2[t].begin(), p2[t].end(), 0.0);
        kernel.single_rows(S.data(), N, N, cut[t], cut[t + 1], w1.data(), w2.data(), p1[t].data(), p2[t].data());
      }
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    std::printf("%zu,%d,%s,%zu,%.2f,%.3f,%.1f\n", N, threads, kernel.name, total, 1e3 * best, 1e9 * best / total,
                4.0 * total / best / 1e9);
  }
}
