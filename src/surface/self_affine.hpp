#pragma once
// A random self-affine rough surface by Fourier filtering: Gaussian random phases and amplitudes
// shaped by the isotropic power spectral density
//   C(q) = C0                       for q_L ≤ q < q_r   (roll-off plateau)
//   C(q) = C0 (q / q_r)^(−2(1+H))   for q_r ≤ q ≤ q_s
//   C(q) = 0                        otherwise (q_L = 2π/L, the box's own wavevector)
// (Persson et al., J. Phys.: Condens. Matter 17, R1, 2005; Jacobs, Junge & Pastewka, Surf. Topogr.
// 5, 013001, 2017), scaled to a prescribed rms height or rms slope. Seeded and reproducible.
#include <cstdint>

#include "surface/height_map.hpp"

namespace asperity {

struct SelfAffineSpec {
  std::size_t n = 256;              // pixels per side (even)
  double length_m = 0;              // side L of the periodic box
  double hurst = 0.8;               // H in (0, 1)
  double rolloff_wavelength_m = 0;  // λ_r = 2π/q_r (≤ L); 0: no plateau (λ_r = L)
  double short_wavelength_m = 0;    // λ_s = 2π/q_s (≥ 2 pixels); 0: the Nyquist wavelength
  double rms_height_m = 0;          // one of the two, the other 0
  double rms_slope = 0;
  std::uint64_t seed = 1;
};

// std::invalid_argument naming the field when the spec cannot be made.
HeightMap self_affine_surface(const SelfAffineSpec& spec);

}  // namespace asperity
