#include "surface/self_affine.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "surface/fft_planner.hpp"

namespace asperity {

HeightMap self_affine_surface(const SelfAffineSpec& s) {
  const auto bad = [](const char* field, const char* why) {
    throw std::invalid_argument(std::string("self-affine surface: ") + field + ": " + why);
  };
  if (s.n < 4 || s.n % 2 || s.n > 16384) bad("n", "an even number of pixels in [4, 16384]");
  if (!(s.length_m > 0) || !std::isfinite(s.length_m)) bad("length", "must be positive");
  if (!(s.hurst > 0 && s.hurst < 1)) bad("hurst", "must be in (0, 1)");
  const double pixel = s.length_m / static_cast<double>(s.n);
  const double lr = s.rolloff_wavelength_m > 0 ? s.rolloff_wavelength_m : s.length_m;
  const double ls = s.short_wavelength_m > 0 ? s.short_wavelength_m : 2 * pixel;
  if (!(lr <= s.length_m * (1 + 1e-12)) || !(ls >= 2 * pixel * (1 - 1e-12)) || !(ls < lr))
    bad("wavelengths", "need 2 pixels <= short < roll-off <= length");
  if ((s.rms_height_m > 0) == (s.rms_slope > 0) || !std::isfinite(s.rms_height_m) || !std::isfinite(s.rms_slope))
    bad("rms", "give exactly one of rms height and rms slope, positive");

  const std::size_t n = s.n, nc = n / 2 + 1;
  const double qL = 2 * std::numbers::pi / s.length_m, qr = 2 * std::numbers::pi / lr, qs = 2 * std::numbers::pi / ls;
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  HeightMap m;
  m.n = n;
  m.pixel_m = pixel;
  m.h_m.assign(n * n, 0.0);
  {
    FftBuffers fft(n);  // c2r of the half spectrum (rows ky, columns kx ≥ 0)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < nc; ++j) {
        const double ky =
            static_cast<double>(i <= n / 2 ? static_cast<long>(i) : static_cast<long>(i) - static_cast<long>(n));
        const double q = qL * std::hypot(ky, static_cast<double>(j));
        double amp = 0;
        if (q >= qL * (1 - 1e-12) && q <= qs * (1 + 1e-12)) amp = std::pow(std::max(q, qr) / qr, -(1 + s.hurst));  // √C
        const double re = gauss(rng), im = gauss(rng);  // drawn for every mode: the seed fixes them all
        fft.spectrum()[i * nc + j][0] = amp * re;
        fft.spectrum()[i * nc + j][1] = amp * im;
      }
    // A real surface has a Hermitian spectrum: the columns kx = 0 and kx = n/2 of the half
    // spectrum hold each mode twice (ky and −ky), conjugates of each other, and the four
    // self-conjugate modes are real. (FFTW's c2r would otherwise drop the non-Hermitian half of
    // them, halving the power on those columns.)
    fftw_complex* X = fft.spectrum();
    for (const std::size_t j : {std::size_t{0}, n / 2}) {
      for (std::size_t i = n / 2 + 1; i < n; ++i) {
        X[i * nc + j][0] = X[(n - i) * nc + j][0];
        X[i * nc + j][1] = -X[(n - i) * nc + j][1];
      }
      X[j][1] = 0;
      X[(n / 2) * nc + j][1] = 0;
    }
    X[0][0] = X[0][1] = 0;  // zero mean
    fft.inverse();
    for (std::size_t k = 0; k < n * n; ++k) m.h_m[k] = fft.real()[k];
  }
  const double scale = s.rms_height_m > 0 ? s.rms_height_m / rms_height(m) : s.rms_slope / rms_slope(m);
  for (double& h : m.h_m) h *= scale;
  return m;
}

}  // namespace asperity
