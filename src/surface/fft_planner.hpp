#pragma once
// FFTW buffers and plans for one n × n real field and its half spectrum (n × (n/2 + 1)), planned
// with FFTW_ESTIMATE (the same algorithm every run, so the same bits) under the one lock FFTW's
// planner needs (its plans are not thread-safe to make or destroy; executing them is). A plan may
// use several threads (libfftw3_threads): FFTW splits the loops of one transform among them, each
// thread computing the same numbers as one thread would (the bits do not depend on the count:
// tests/unit/bench/test_surface_contact_speed.cpp).
#include <fftw3.h>

#include <cstddef>
#include <mutex>

namespace asperity {

// FFTW's planner lock, held while plans are made or destroyed; the first call also starts FFTW's
// threads (fftw_init_threads, once per process).
std::unique_lock<std::mutex> lock_fftw_planner();

class FftBuffers {
 public:
  explicit FftBuffers(std::size_t n, int threads = 1);
  ~FftBuffers();
  FftBuffers(const FftBuffers&) = delete;
  FftBuffers& operator=(const FftBuffers&) = delete;
  double* real() { return real_; }
  fftw_complex* spectrum() { return spec_; }
  void forward() { fftw_execute(forward_); }  // real → spectrum (unnormalised)
  void inverse() { fftw_execute(inverse_); }  // spectrum → real (unnormalised: × n² after forward)

 private:
  double* real_ = nullptr;
  fftw_complex* spec_ = nullptr;
  fftw_plan forward_ = nullptr, inverse_ = nullptr;
};

}  // namespace asperity
