#include "bench/contact.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "surface/fft_planner.hpp"
#include "surface/normal_contact.hpp"
#include "surface/self_affine.hpp"
#include "surface/tangential_contact.hpp"

namespace asperity {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

long max_rss_kB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

}  // namespace

// A PDMS-like sphere (R 9.5 mm, E* 2.13 MPa) at the largest stand-in load's scale (4 N) on a
// 4 mm box, carrying a self-affine surface (H 0.8, λ_r 1 mm, λ_s 4 pixels, h_rms 1 µm): an
// illustration of the workload, not a measured topography.
HeightMap contact_bench_surface(std::size_t n) {
  SelfAffineSpec s;
  s.n = n;
  s.length_m = 4e-3;
  s.hurst = 0.8;
  s.rolloff_wavelength_m = 1e-3;
  s.short_wavelength_m = 4 * s.length_m / static_cast<double>(n);
  s.rms_height_m = 1e-6;
  s.seed = 3;
  HeightMap m = self_affine_surface(s);
  add_sphere(m, 9.5e-3);
  return m;
}

NormalContactSettings contact_bench_settings(double tolerance) {
  NormalContactSettings c;
  c.E_star_Pa = 2.13e6;
  c.load_N = 4.0;
  c.tolerance = tolerance;
  return c;
}

TangentialContactSettings tangential_bench_settings(double tolerance) {
  TangentialContactSettings t;
  t.nu = 0.5;
  t.E_Pa = contact_bench_settings(tolerance).E_star_Pa * (1 - t.nu * t.nu);
  t.tolerance = tolerance;
  return t;
}

std::vector<ContactBenchRow> run_contact_bench(const ContactBenchOptions& opt) {
  std::vector<std::size_t> sizes = opt.sizes;
  std::sort(sizes.begin(), sizes.end());
  std::vector<ContactBenchRow> rows;
  for (const std::size_t n : sizes) {
    const HeightMap m = contact_bench_surface(n);
    NormalContactSettings c = contact_bench_settings(opt.tolerance);
    c.threads = opt.threads;
    ContactBenchRow r;
    r.n = n;
    r.threads = opt.threads;
    const auto t0 = Clock::now();
    const NormalContact res = solve_normal_contact(m, c);
    r.wall_s = seconds_since(t0);
    r.iterations = res.iterations;
    r.coarse_iterations = res.coarse_iterations;
    r.convolutions = res.convolutions;
    r.converged = res.converged;
    r.per_iteration_s = r.wall_s / std::max(1, res.iterations);
    r.area_m2 = res.area_m2;
    {
      TangentialContactSettings ts = tangential_bench_settings(opt.tolerance);
      ts.threads = opt.threads;
      const auto t2 = Clock::now();
      TangentialContact t(n, m.pixel_m, coulomb_bound(res, 0.5), ts);
      const TangentialState st = t.solve(0.5 * t.full_sliding_displacement_m());
      r.tangential_wall_s = seconds_since(t2);
      r.tangential_iterations = st.iterations;
      r.tangential_convolutions = st.convolutions;
      r.tangential_converged = st.converged;
    }
    {
      FftBuffers f(2 * n, opt.threads);
      for (std::size_t k = 0; k < 4 * n * n; ++k) f.real()[k] = std::sin(1e-3 * static_cast<double>(k));
      std::vector<double> times;
      for (int rep = 0; rep < 7; ++rep) {
        const auto t1 = Clock::now();
        f.forward();
        f.inverse();
        times.push_back(seconds_since(t1));
      }
      std::sort(times.begin(), times.end());
      r.fft_pair_s = times[times.size() / 2];
    }
    r.max_rss_kB = max_rss_kB();
    if (opt.log)
      *opt.log << "  " << n << "^2 (padded " << 2 * n << "^2), " << r.threads << " thread(s): " << r.iterations
               << " CG iterations (+ " << r.coarse_iterations << " on coarser grids), " << r.convolutions
               << " FFT pairs" << (r.converged ? "" : " (NOT converged)") << ", " << r.wall_s << " s, "
               << r.per_iteration_s * 1e3 << " ms per iteration = " << r.per_iteration_s / (2 * r.fft_pair_s)
               << " x two FFT pairs (" << r.fft_pair_s * 1e3 << " ms each); tangential solve " << r.tangential_wall_s
               << " s = " << r.tangential_wall_s / r.wall_s << " x the normal solve, " << r.tangential_iterations
               << " iterations, " << r.tangential_convolutions << " FFT pairs"
               << (r.tangential_converged ? "" : " (NOT converged)") << ", peak RSS " << r.max_rss_kB / 1024 << " MB"
               << std::endl;
    rows.push_back(r);
  }
  return rows;
}

void write_contact_bench(const fs::path& dir, const std::vector<ContactBenchRow>& rows) {
  std::ostringstream o;
  o << "n,padded,threads,iterations,coarse_iterations,convolutions,converged,wall_s,per_iteration_s,fft_pair_s,per_"
       "iteration_over_two_fft_pairs,area_m2,tangential_wall_s,tangential_over_normal,tangential_iterations,tangential_"
       "convolutions,tangential_converged,max_rss_kB\n";
  for (const auto& r : rows)
    o << r.n << ',' << 2 * r.n << ',' << r.threads << ',' << r.iterations << ',' << r.coarse_iterations << ','
      << r.convolutions << ',' << (r.converged ? "true" : "false") << ',' << io::csv_number(r.wall_s) << ','
      << io::csv_number(r.per_iteration_s) << ',' << io::csv_number(r.fft_pair_s) << ','
      << io::csv_number(r.per_iteration_s / (2 * r.fft_pair_s)) << ',' << io::csv_number(r.area_m2) << ','
      << io::csv_number(r.tangential_wall_s) << ',' << io::csv_number(r.tangential_wall_s / r.wall_s) << ','
      << r.tangential_iterations << ',' << r.tangential_convolutions << ','
      << (r.tangential_converged ? "true" : "false") << ',' << r.max_rss_kB << '\n';
  fs::create_directories(dir);
  io::write_text_file(dir / "contact.csv", o.str());
}

}  // namespace asperity
