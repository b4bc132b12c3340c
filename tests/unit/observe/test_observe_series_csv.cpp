// observe/series_csv.hpp: the bytes of series.csv.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "observe/series_csv.hpp"

using namespace asperity;

TEST_CASE("series.csv header is all series in canonical order", "[observe][csv]") {
  std::ostringstream out;
  Sample s{0.5, 1e-6, 2e-5, 0.25, 1.25e-5, 7, 1200};
  write_series_csv(out, {s}, {"n_intact", "t", "A", "X", "Q", "V", "n_slipping"});
  CHECK(out.str() ==
        "t,X,V,Q,A,n_slipping,n_intact\n0.5,9.9999999999999995e-07,2.0000000000000002e-05,"
        "0.25,1.2500000000000001e-05,7,1200\n");
  std::ostringstream sub;
  write_series_csv(sub, {s}, {"A", "t"});
  CHECK(sub.str() == "t,A\n0.5,1.2500000000000001e-05\n");
  std::ostringstream bad;
  CHECK_THROWS_AS(write_series_csv(bad, {s}, {"t", "F"}), std::invalid_argument);
}

TEST_CASE("series.csv reals read back to the same doubles, counts exactly", "[observe][csv]") {
  // Values with no short decimal form: %.17g must round-trip them bit for bit (strtod is the
  // independent reader).
  const Sample s{0.1 + 0.2, 1.0 / 3.0, -2.0 / 7.0, 1e-300 * 3.7, 6.02214076e23 / 7.0, 9007199254740993LL, -1};
  std::ostringstream out;
  write_series_csv(out, {s, s}, {"t", "X", "V", "Q", "A", "n_slipping", "n_intact"});
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  for (int row = 0; row < 2; ++row) {
    REQUIRE(std::getline(in, line));
    std::istringstream fields(line);
    std::string f;
    const double want[] = {s.t, s.X, s.V, s.Q, s.A};
    for (const double w : want) {
      std::getline(fields, f, ',');
      CHECK(std::strtod(f.c_str(), nullptr) == w);
    }
    std::getline(fields, f, ',');
    CHECK(f == "9007199254740993");
    std::getline(fields, f, ',');
    CHECK(f == "-1");
  }
  CHECK_FALSE(std::getline(in, line));
}
