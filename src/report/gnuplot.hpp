#pragma once
// Runs a gnuplot script (the plots of every command go through here). Data travel inside the
// script as named data blocks ($name << EOD), so a figure needs no side files.
#include <filesystem>
#include <string>
#include <vector>

#include "observe/sample.hpp"

namespace asperity {

// True when `gnuplot` is on the PATH.
bool gnuplot_available();

// A data block `$name << EOD ... EOD` with one row per entry of `rows` (values %.10g; NaN rows
// are written as blank lines, which gnuplot draws as gaps).
std::string gnuplot_block(const std::string& name, const std::vector<std::vector<double>>& rows);

// A shell word quoting `s` (single quotes), for paths handed to std::system.
std::string shell_quote(const std::string& s);

// Renders `png` from `script` (which must not set the terminal or output): the script is
// prefixed with `set terminal pngcairo size W,H noenhanced` and an output to a hidden temporary
// name that is renamed into place, so a failed plot never leaves a half-written PNG. Returns
// false (writing nothing) when gnuplot is missing or fails.
bool render_png(const std::filesystem::path& png, const std::string& script, int width = 1200,
                int height = 800);

// Runs `script` with `workdir` as current directory. Throws std::runtime_error naming the
// script's first output line and gnuplot's exit status when gnuplot is missing or fails.
void run_gnuplot(const std::filesystem::path& workdir, const std::string& script);

}  // namespace asperity
