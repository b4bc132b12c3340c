// The committed coverage runs (results/coverage/, SYNTHETIC; docs/calibration.md, "The recovery
// matrix" and "The open light-load case"): is a fit's σ the scatter of its optimum over noise
// draws? Where it is, z = (value − truth)/σ over many certified fits behaves as unit normals, and
// the root mean square of n of them lies in the band that sqrt(χ²_n / n) gives 90 % of draws.
#include <boost/math/distributions/chi_squared.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "io/csv.hpp"

using namespace asperity;

namespace {

struct Band {
  double lo, hi;
};

// The 90 % band of the rms of n unit normals: sqrt(χ²_n quantile / n) at 5 % and 95 %.
Band rms_band(std::size_t n) {
  const boost::math::chi_squared chi2(static_cast<double>(n));
  return {std::sqrt(boost::math::quantile(chi2, 0.05) / n), std::sqrt(boost::math::quantile(chi2, 0.95) / n)};
}

double rms(const std::vector<double>& z) {
  double s = 0;
  for (const double x : z) s += x * x;
  return std::sqrt(s / z.size());
}

io::TextTable committed(const char* name) {
  const std::filesystem::path file = std::filesystem::path(ASPERITY_SOURCE_DIR) / "results/coverage" / name;
  io::TextTable t = io::read_text_table(file, file.generic_string(), 10000);
  REQUIRE(t.size() > 0);
  return t;
}

}  // namespace

TEST_CASE(
    "the committed coverage: the Hessian's sigma at truth a, and the bootstrap's at truth b, cover as unit normals",
    "[studies][coverage]") {
  // The band itself, against the values docs/calibration.md quotes from a simulation.
  CHECK(rms_band(12).lo == Approx(0.66).margin(0.01));
  CHECK(rms_band(12).hi == Approx(1.32).margin(0.01));
  CHECK(rms_band(42).lo == Approx(0.82).margin(0.01));
  CHECK(rms_band(42).hi == Approx(1.18).margin(0.01));

  SECTION("truth a, the independent model at the light load, Hessian's sigma (coverage.csv)") {
    const io::TextTable t = committed("coverage.csv");
    std::vector<double> z;
    for (std::size_t r = 0; r < t.size(); ++r)
      for (const std::string k : {"model.alpha_b", "model.epsilon", "model.eta"}) {
        // Each z recomputed from its value and sigma against the truth the recipe generated.
        const double truth = k == "model.alpha_b" ? 0.7e-15 : (k == "model.epsilon" ? 0.9 : 100.0);
        const double zr = (t.number(r, k) - truth) / t.number(r, k + "_sigma");
        CHECK(zr == Approx(t.number(r, k + "_z")).margin(1e-3));
        z.push_back(zr);
      }
    REQUIRE(z.size() == 36);
    const Band b = rms_band(z.size());
    INFO("rms z " << rms(z) << " in [" << b.lo << ", " << b.hi << "]");
    CHECK(rms(z) > b.lo);
    CHECK(rms(z) < b.hi);
  }

  SECTION("truth b at the light load: the Hessian's sigma too small, the bootstrap's right (coverage_truth_b.csv)") {
    const io::TextTable t = committed("coverage_truth_b.csv");
    std::vector<double> hessian, bootstrap;
    for (std::size_t r = 0; r < t.size(); ++r) {
      if (!t.yes_no(r, "certified")) continue;
      const double miss = t.number(r, "value") - t.number(r, "truth");
      hessian.push_back(miss / t.number(r, "sigma_hessian"));
      bootstrap.push_back(miss / t.number(r, "sigma_bootstrap"));
      CHECK(hessian.back() == Approx(t.number(r, "z_hessian")).margin(1e-3));
      CHECK(bootstrap.back() == Approx(t.number(r, "z_bootstrap")).margin(1e-3));
    }
    REQUIRE(bootstrap.size() == 42);  // 14 certified fits of 20, three parameters each
    const Band b = rms_band(bootstrap.size());
    INFO("rms z: Hessian " << rms(hessian) << ", bootstrap " << rms(bootstrap) << "; band [" << b.lo << ", " << b.hi
                           << "]");
    CHECK(rms(hessian) > b.hi);
    CHECK(rms(bootstrap) > b.lo);
    CHECK(rms(bootstrap) < b.hi);
  }
}
