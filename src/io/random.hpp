#pragma once
// Reproducible random numbers: a draw is a quantile of a uniform, so its bytes depend only on
// std::mt19937_64 (whose output sequence the C++ standard specifies), on our own 53-bit
// conversion to a double in (0, 1), and on Boost.Math's quantiles; never on the standard
// library's <random> distributions, whose algorithms are unspecified.
#include <cstdint>
#include <random>

namespace asperity::io {

// Uniform doubles in the open interval (0, 1) from the top 53 bits of std::mt19937_64:
// u = (k + 1/2) / 2^53, k ∈ [0, 2^53). Never returns 0 or 1, so quantiles stay finite.
class Uniform01 {
 public:
  explicit Uniform01(std::uint64_t seed) : gen_(seed) {}
  double operator()() {
    const std::uint64_t k = gen_() >> 11;
    return (static_cast<double>(k) + 0.5) * 0x1.0p-53;
  }

 private:
  std::mt19937_64 gen_;
};

// SplitMix64 finaliser: a fixed bijection of 64-bit integers, used to derive independent
// seeds (per experiment, per stream) from one base seed.
std::uint64_t splitmix64(std::uint64_t x);

// Standard normal quantile Φ⁻¹(u) and distribution function Φ(z) (Boost.Math).
double normal_quantile(double u);
double normal_cdf(double z);

}  // namespace asperity::io
