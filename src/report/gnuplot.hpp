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

// Renders `figure` (.png, .svg or .pdf: pngcairo, svg or pdfcairo; W × H pixels, 100 per inch
// for PDF) from `script` (which must not set the terminal or output): gnuplot writes a hidden
// temporary file of a fixed-pattern name in the same folder, which is tagged as ours (PNG) and
// renamed into place, so a failed plot never leaves a half-written figure. The whole script,
// data included, is kept next to the figure as FIGURE-STEM.gp (`gnuplot FIGURE-STEM.gp` redraws
// it: restyle it there), unless a file of that name exists that asperity did not write.
// Returns false when gnuplot is missing or fails (the script is still kept), with the reason in
// `*error` ("gnuplot not found on the PATH" or gnuplot's first error line).
bool render_plot(const std::filesystem::path& figure, const std::string& script, int width = 1200,
                 int height = 800, std::string* error = nullptr);

// Keeps `script` (full: terminal and output included) as `gp`, unless a file exists there that
// asperity did not write (its first line is not our header). Returns whether it was written.
bool keep_plot_script(const std::filesystem::path& gp, const std::string& script);

// The script render_plot keeps for `figure`: FIGURE-STEM.gp beside it.
std::filesystem::path plot_script_path(const std::filesystem::path& figure);

// True when `figure` was written by asperity: a PNG tagged by render_plot (tEXt chunk
// "Software" = "asperity"), or an SVG/PDF whose kept script (ours) names it. The only existing
// files a plot may replace.
bool png_is_ours(const std::filesystem::path& figure);

}  // namespace asperity
