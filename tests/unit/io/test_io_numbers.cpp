// io/numbers.hpp: report cells (format_cell) print as printf does, and as "–" without a value;
// format_double reads back to exactly the same double.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "io/numbers.hpp"

using namespace asperity::io;

TEST_CASE("report cells print as printf, and a dash where there is no value", "[io][numbers]") {
  for (const double x : {0.0, -1.5, 3.296430016634404, 7.25e-16, 1e300}) {
    char b[64];
    std::snprintf(b, sizeof b, "%.4g", x);
    CHECK(format_cell("%.4g", x) == b);
  }
  CHECK(format_cell("%.3f", std::nan("")) == "–");
  CHECK(format_cell("%.3f", std::numeric_limits<double>::infinity()) == "–");
  CHECK(format_cell("%.3f", -std::numeric_limits<double>::infinity()) == "–");
}

TEST_CASE("format_double reads back to the same double", "[io][numbers]") {
  for (const double x : {0.1, 7.25e-16, 3.296430016634404, -2.5e300, 5e-324}) {
    const std::string s = format_double(x);
    CHECK(std::strtod(s.c_str(), nullptr) == x);
  }
}
