#pragma once
// Runs gnuplot, the one external program the project starts. It is found on the PATH and
// started with posix_spawn (no shell); the script goes to its standard input, so nothing in a
// script (which may hold text from inputs, quoted by report/gnuplot.hpp) is ever a command line.
#include <filesystem>
#include <string>

namespace asperity::io {

// True when `gnuplot` is on the PATH.
bool gnuplot_available();

// Runs `script` with `workdir` as current directory (relative file names in the script refer to
// it). Throws std::runtime_error naming gnuplot's first error line and its exit status when
// gnuplot is missing or fails.
void run_gnuplot(const std::filesystem::path& workdir, const std::string& script);

}  // namespace asperity::io
