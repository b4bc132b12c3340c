#pragma once
// How the bench writers spell an error that could not be measured.
#include <cmath>
#include <string>

#include "io/numbers.hpp"

namespace asperity::bench_text {

// Shortest text that reads back to exactly x ("nan" when not finite): errors can be
// recomputed from a CSV.
inline std::string exact(double x) { return std::isfinite(x) ? io::format_double(x) : "nan"; }

}  // namespace asperity::bench_text
