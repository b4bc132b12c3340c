#include "surface/fft_planner.hpp"

#include <algorithm>
#include <new>

namespace asperity {

std::unique_lock<std::mutex> lock_fftw_planner() {
  // FFTW's planner is not thread-safe: plans are made and destroyed under this lock (FFTW's own
  // requirement; the one process-wide state of surface/).
  static std::mutex m;
  std::unique_lock<std::mutex> lock(m);
  static const bool threads_ready = fftw_init_threads() != 0;
  (void)threads_ready;  // if it failed, fftw_plan_with_nthreads is ignored: one thread
  return lock;
}

FftBuffers::FftBuffers(std::size_t n, int threads) {
  const std::size_t nc = n / 2 + 1;
  real_ = fftw_alloc_real(n * n);
  spec_ = fftw_alloc_complex(n * nc);
  if (!real_ || !spec_) {
    fftw_free(real_), fftw_free(spec_);
    throw std::bad_alloc();
  }
  const auto lock = lock_fftw_planner();
  fftw_plan_with_nthreads(std::max(1, threads));
  const int N = static_cast<int>(n);
  forward_ = fftw_plan_dft_r2c_2d(N, N, real_, spec_, FFTW_ESTIMATE);
  inverse_ = fftw_plan_dft_c2r_2d(N, N, spec_, real_, FFTW_ESTIMATE);
}

FftBuffers::~FftBuffers() {
  {
    const auto lock = lock_fftw_planner();
    fftw_destroy_plan(forward_);
    fftw_destroy_plan(inverse_);
  }
  fftw_free(real_), fftw_free(spec_);
}

}  // namespace asperity
