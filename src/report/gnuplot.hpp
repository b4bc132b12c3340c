#pragma once
// Runs a gnuplot script (the plots of every command go through here). Data travel inside the
// script as named data blocks ($name << EOD), so a figure needs no side files.
//
// Text from inputs (experiment and campaign names, paths, --where values) is data, never code:
// it enters a script only through gnuplot_quote(), and gnuplot is started without a shell
// (io/gnuplot_runner.hpp: posix_spawn of `gnuplot` found on the PATH, script on its standard input).
#include <filesystem>
#include <string>
#include <vector>

#include "io/gnuplot_runner.hpp"  // gnuplot_available, run_gnuplot: the runner the plots use

namespace asperity {

// A gnuplot string expression whose value is `text`: single-quoted pieces (inside single quotes
// gnuplot expands nothing: no backquote commands, no macros, no backslash escapes) joined by `.`
// with "'" for each quote. Control characters (bytes below 0x20 and 0x7f), which could end the
// command line, become '?'. Every other byte, including UTF-8, is kept. Usable wherever gnuplot
// takes a string (titles, labels, tic labels, key entries, set output).
std::string gnuplot_quote(const std::string& text);

// A data block `$name << EOD ... EOD` with one row per entry of `rows` (values %.10g; NaN rows
// are written as blank lines, which gnuplot draws as gaps).
std::string gnuplot_block(const std::string& name, const std::vector<std::vector<double>>& rows);

// Renders `png` from `script` (which must not set the terminal or output): the script is
// prefixed with `set terminal pngcairo size W,H noenhanced` and an output to a hidden temporary
// file of a fixed-pattern name in the same folder, which is tagged as ours (see png_is_ours) and
// renamed into place, so a failed plot never leaves a half-written PNG. Returns false (writing
// nothing) when gnuplot is missing or fails, with gnuplot's first error line in `*error`.
bool render_png(const std::filesystem::path& png, const std::string& script, int width = 1200,
                int height = 800, std::string* error = nullptr);

// True when `png` is a PNG file written by render_png (it carries a tEXt chunk
// "Software" = "asperity"): the only existing files a plot may replace.
bool png_is_ours(const std::filesystem::path& png);

}  // namespace asperity
