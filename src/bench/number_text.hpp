#pragma once
// Number formatting shared by the bench writers.
#include <cmath>
#include <cstdio>
#include <string>

#include "io/csv.hpp"

namespace asperity::bench_text {

// %.<digits>g, for tables meant to be read.
inline std::string g(double x, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}
// Shortest text that reads back to exactly x ("nan" when not finite): errors can be
// recomputed from a CSV.
inline std::string exact(double x) { return std::isfinite(x) ? csv_number(x) : "nan"; }

}  // namespace asperity::bench_text
