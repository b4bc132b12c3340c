#include "io/random.hpp"

#include <boost/math/distributions/normal.hpp>

namespace asperity::io {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

double normal_quantile(double u) {
  static const boost::math::normal_distribution<double> z(0.0, 1.0);
  return boost::math::quantile(z, u);
}

double normal_cdf(double x) {
  static const boost::math::normal_distribution<double> z(0.0, 1.0);
  return boost::math::cdf(z, x);
}

}  // namespace asperity::io
