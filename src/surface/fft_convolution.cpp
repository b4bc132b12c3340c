#include "surface/fft_convolution.hpp"

#include <algorithm>
#include <cstring>
#include <new>

namespace asperity {

using pixel_loops::kParallelFrom;

PaddedConvolution::PaddedConvolution(std::size_t n, std::vector<double> even, pixel_loops::Workers& w)
    : n_(n), N_(2 * n), nc_(n + 1), w_(w) {
  spec_ = fftw_alloc_complex(n_ * nc_);
  if (!spec_) throw std::bad_alloc();
  const std::size_t T = static_cast<std::size_t>(w_.count());
  for (std::size_t t = 0; t < T; ++t) {
    row_buf_.push_back(fftw_alloc_real(kRows * N_));
    col_buf_.push_back(fftw_alloc_complex(kCols * N_));
    if (!row_buf_.back() || !col_buf_.back()) {
      release();
      throw std::bad_alloc();
    }
  }
  const auto lock = lock_fftw_planner();
  fftw_plan_with_nthreads(1);
  {
    // The kernel's spectrum: K(ky, kx) = Σ over the wrapped offsets = FFTW's REDFT00 of the
    // (n + 1)² even values, real; stored column by column (kx), ky = 0..n, divided by N².
    const int m = static_cast<int>(nc_);
    fftw_plan dct = fftw_plan_r2r_2d(m, m, even.data(), even.data(), FFTW_REDFT00, FFTW_REDFT00, FFTW_ESTIMATE);
    fftw_execute(dct);
    fftw_destroy_plan(dct);
    const double scale = 1.0 / static_cast<double>(N_ * N_);
    kernel_.resize(nc_ * nc_);
    for (std::size_t ky = 0; ky < nc_; ++ky)
      for (std::size_t kx = 0; kx < nc_; ++kx) kernel_[kx * nc_ + ky] = even[ky * nc_ + kx] * scale;
  }
  const int len = static_cast<int>(N_), cols = static_cast<int>(nc_);
  for (int k = 0; k < 2; ++k) {
    const int rows = k == 0 ? static_cast<int>(kRows) : static_cast<int>(n_ % kRows);
    const int many = k == 0 ? static_cast<int>(kCols) : static_cast<int>(nc_ % kCols);
    if (rows > 0) {
      rows_forward_[k] =
          fftw_plan_many_dft_r2c(1, &len, rows, row_buf_[0], nullptr, 1, len, spec_, nullptr, 1, cols, FFTW_ESTIMATE);
      rows_inverse_[k] =
          fftw_plan_many_dft_c2r(1, &len, rows, spec_, nullptr, 1, cols, row_buf_[0], nullptr, 1, len, FFTW_ESTIMATE);
    }
    if (many > 0) {
      cols_forward_[k] = fftw_plan_many_dft(1, &len, many, col_buf_[0], nullptr, 1, len, col_buf_[0], nullptr, 1, len,
                                            FFTW_FORWARD, FFTW_ESTIMATE);
      cols_inverse_[k] = fftw_plan_many_dft(1, &len, many, col_buf_[0], nullptr, 1, len, col_buf_[0], nullptr, 1, len,
                                            FFTW_BACKWARD, FFTW_ESTIMATE);
    }
  }
}

void PaddedConvolution::apply(const std::vector<double>& in, std::vector<double>& out) {
  const std::ptrdiff_t row_blocks = static_cast<std::ptrdiff_t>((n_ + kRows - 1) / kRows);
  const std::ptrdiff_t col_blocks = static_cast<std::ptrdiff_t>((nc_ + kCols - 1) / kCols);
  const double* K = kernel_.data();
  const bool parallel = n_ * n_ >= kParallelFrom;
  // Rows: the n nonzero rows of the padded field, r2c.
  w_.run(static_cast<std::size_t>(row_blocks), parallel, [&](std::size_t b, std::size_t t) {
    double* rb = row_buf_[t];
    const std::size_t i0 = b * kRows, rows = std::min(kRows, n_ - i0);
    for (std::size_t r = 0; r < rows; ++r) {
      std::copy(&in[(i0 + r) * n_], &in[(i0 + r) * n_] + n_, rb + r * N_);
      std::fill(rb + r * N_ + n_, rb + (r + 1) * N_, 0.0);
    }
    fftw_execute_dft_r2c(rows_forward_[rows == kRows ? 0 : 1], rb, spec_ + i0 * nc_);
  });
  // Columns: gathered (rows n..N−1 zero), forward, × kernel, backward, the first n scattered back.
  w_.run(static_cast<std::size_t>(col_blocks), parallel, [&](std::size_t b, std::size_t t) {
    fftw_complex* cb = col_buf_[t];
    const std::size_t c0 = b * kCols, cols = std::min(kCols, nc_ - c0);
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t c = 0; c < cols; ++c) {
        cb[c * N_ + i][0] = spec_[i * nc_ + c0 + c][0];
        cb[c * N_ + i][1] = spec_[i * nc_ + c0 + c][1];
      }
    for (std::size_t c = 0; c < cols; ++c)
      std::memset(static_cast<void*>(cb + c * N_ + n_), 0, sizeof(fftw_complex) * (N_ - n_));
    const int which = cols == kCols ? 0 : 1;
    fftw_execute_dft(cols_forward_[which], cb, cb);
    for (std::size_t c = 0; c < cols; ++c) {
      fftw_complex* x = cb + c * N_;
      const double* k = K + (c0 + c) * nc_;
      for (std::size_t ky = 0; ky <= n_; ++ky) x[ky][0] *= k[ky], x[ky][1] *= k[ky];
      for (std::size_t ky = n_ + 1; ky < N_; ++ky) x[ky][0] *= k[N_ - ky], x[ky][1] *= k[N_ - ky];
    }
    fftw_execute_dft(cols_inverse_[which], cb, cb);
    for (std::size_t i = 0; i < n_; ++i)
      for (std::size_t c = 0; c < cols; ++c) {
        spec_[i * nc_ + c0 + c][0] = cb[c * N_ + i][0];
        spec_[i * nc_ + c0 + c][1] = cb[c * N_ + i][1];
      }
  });
  // Rows back: c2r of the n wanted rows, their first n values.
  w_.run(static_cast<std::size_t>(row_blocks), parallel, [&](std::size_t b, std::size_t t) {
    double* rb = row_buf_[t];
    const std::size_t i0 = b * kRows, rows = std::min(kRows, n_ - i0);
    fftw_execute_dft_c2r(rows_inverse_[rows == kRows ? 0 : 1], spec_ + i0 * nc_, rb);
    for (std::size_t r = 0; r < rows; ++r) std::copy(rb + r * N_, rb + r * N_ + n_, &out[(i0 + r) * n_]);
  });
}

void PaddedConvolution::release() {
  {
    const auto lock = lock_fftw_planner();
    for (fftw_plan* ps : {rows_forward_, rows_inverse_, cols_forward_, cols_inverse_})
      for (int k = 0; k < 2; ++k)
        if (ps[k]) fftw_destroy_plan(ps[k]), ps[k] = nullptr;
  }
  for (double* b : row_buf_) fftw_free(b);
  for (fftw_complex* b : col_buf_) fftw_free(b);
  row_buf_.clear(), col_buf_.clear();
  fftw_free(spec_), spec_ = nullptr;
}

}  // namespace asperity
