#pragma once
// FFTW buffers and plans for one n × n real field and its half spectrum (n × (n/2 + 1)), planned
// with FFTW_ESTIMATE (the same algorithm every run, so the same bits) under the one lock FFTW's
// planner needs (its plans are not thread-safe to make or destroy; executing them is).
#include <fftw3.h>

#include <cstddef>

namespace asperity {

class FftBuffers {
 public:
  explicit FftBuffers(std::size_t n);
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
