#pragma once
// Convolution of an n × n field with a fixed kernel by FFT (FFTW), the elastic operator of the
// boundary-element contact solvers: periodic (the kernel given by its spectrum) or isolated (the
// field zero-padded to 2n × 2n, the kernel given by its values at the offsets 0..n, even in both
// directions). The bits of a result do not depend on the number of threads.
#include <cstddef>
#include <vector>

#include "surface/fft_planner.hpp"
#include "surface/pixel_loops.hpp"

namespace asperity {

// Convolution with a fixed kernel on an n × n field.
class Convolution {
 public:
  virtual ~Convolution() = default;
  virtual void apply(const std::vector<double>& in, std::vector<double>& out) = 0;  // out = kernel ∗ in
};

// Periodic: the kernel given by its spectrum, value at the wavevector indices (ky, kx), kx ≥ 0.
class PeriodicConvolution final : public Convolution {
 public:
  template <class F>
  PeriodicConvolution(std::size_t n, pixel_loops::Workers& w, F spectrum)
      : n_(n), nc_(n / 2 + 1), w_(w), fft_(n, w.count()), kernel_(n * nc_) {
    const double scale = 1.0 / static_cast<double>(n * n);
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t j = 0; j < nc_; ++j) {
        const long ky = i <= n_ / 2 ? static_cast<long>(i) : static_cast<long>(i) - static_cast<long>(n_);
        kernel_[i * nc_ + j] = spectrum(ky, static_cast<long>(j)) * scale;
      }
  }
  void apply(const std::vector<double>& in, std::vector<double>& out) override {
    std::copy(in.begin(), in.end(), fft_.real());
    fft_.forward();
    fftw_complex* spec = fft_.spectrum();
    pixel_loops::for_each_pixel(n_ * nc_, w_,
                                [&](std::size_t k) { spec[k][0] *= kernel_[k], spec[k][1] *= kernel_[k]; });
    fft_.inverse();
    std::copy(fft_.real(), fft_.real() + n_ * n_, out.begin());
  }

 private:
  std::size_t n_, nc_;
  pixel_loops::Workers& w_;
  FftBuffers fft_;
  std::vector<double> kernel_;  // real spectrum, divided by n² (FFTW's transforms are unnormalised)
};

// Isolated: the field zero-padded to N = 2n and convolved with a kernel given by its values at the
// offsets 0..n in each direction (even in both: Love's rectangle), wrapped on the N × N grid. The
// 2-D transform is done as rows then columns, in fixed blocks of rows and of columns shared among
// the threads, each block by the same one-thread FFTW plan (so the bits do not depend on the
// number of threads): the input rows n..N−1 (zero) and the output rows n..N−1 (not wanted) are
// never transformed, and each block of columns is gathered into a contiguous buffer, transformed,
// multiplied by the kernel, transformed back and scattered, in cache: the N × (n + 1) spectrum is
// never stored whole. The kernel is real and even, so its spectrum is real and even: a 2-D DCT-I
// of the (n + 1)² values gives it (ky and N − ky share a value).
class PaddedConvolution final : public Convolution {
 public:
  PaddedConvolution(std::size_t n, std::vector<double> even, pixel_loops::Workers& w);
  ~PaddedConvolution() override { release(); }
  PaddedConvolution(const PaddedConvolution&) = delete;
  PaddedConvolution& operator=(const PaddedConvolution&) = delete;
  void apply(const std::vector<double>& in, std::vector<double>& out) override;

 private:
  static constexpr std::size_t kRows = 4, kCols = 4;  // rows and columns per block (fixed: the bits)
  void release();

  std::size_t n_, N_, nc_;
  pixel_loops::Workers& w_;
  fftw_complex* spec_ = nullptr;        // the n wanted rows' spectra, nc each
  std::vector<double*> row_buf_;        // per thread: kRows padded rows of N
  std::vector<fftw_complex*> col_buf_;  // per thread: kCols columns of N
  std::vector<double> kernel_;          // its real spectrum, column kx holding ky = 0..n, divided by N²
  // [0]: a whole block, [1]: the last, shorter one (if any)
  fftw_plan rows_forward_[2] = {}, rows_inverse_[2] = {}, cols_forward_[2] = {}, cols_inverse_[2] = {};
};
}  // namespace asperity
