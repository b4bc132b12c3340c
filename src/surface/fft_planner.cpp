#include "surface/fft_planner.hpp"

#include <mutex>
#include <new>

namespace asperity {
namespace {

// FFTW's planner is not thread-safe: plans are made and destroyed under this lock (FFTW's own
// requirement; the one process-wide state of surface/).
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

FftBuffers::FftBuffers(std::size_t n) {
  const std::size_t nc = n / 2 + 1;
  real_ = fftw_alloc_real(n * n);
  spec_ = fftw_alloc_complex(n * nc);
  if (!real_ || !spec_) {
    fftw_free(real_), fftw_free(spec_);
    throw std::bad_alloc();
  }
  const std::lock_guard<std::mutex> lock(planner_mutex());
  const int N = static_cast<int>(n);
  forward_ = fftw_plan_dft_r2c_2d(N, N, real_, spec_, FFTW_ESTIMATE);
  inverse_ = fftw_plan_dft_c2r_2d(N, N, spec_, real_, FFTW_ESTIMATE);
}

FftBuffers::~FftBuffers() {
  {
    const std::lock_guard<std::mutex> lock(planner_mutex());
    fftw_destroy_plan(forward_);
    fftw_destroy_plan(inverse_);
  }
  fftw_free(real_), fftw_free(spec_);
}

}  // namespace asperity
