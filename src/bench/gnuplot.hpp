#pragma once
// Renders a PNG with gnuplot (bench figures). The script writes to a temporary name that is
// renamed into place, so a failed plot never leaves a half-written PNG.
#include <filesystem>
#include <string>

namespace asperity {

// `script` must not set the terminal output; it is prefixed with
// `set terminal pngcairo size W,H noenhanced` and `set output '<temp>'`. Returns false (and
// writes nothing) when gnuplot is missing or fails.
bool render_png(const std::filesystem::path& png, const std::string& script, int width = 1200,
                int height = 800);

}  // namespace asperity
