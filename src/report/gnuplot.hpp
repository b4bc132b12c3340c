#pragma once
// Runs a gnuplot script (the plots of every command go through here). Data travel inside the
// script as named data blocks ($name << EOD), so a figure needs no side files.
//
// Text from inputs (experiment and campaign names, paths, --where values) is data, never code:
// it enters a script only through gnuplot_quote() (and figure text only through
// enhanced_literal() inside it, below), and gnuplot is started without a shell
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

// Figure text is gnuplot "enhanced" text: a_b and a_{bc} subscripts, m^2 and m^{2p+2}
// superscripts, UTF-8 Greek (α_b). Markup is written by asperity only; text from inputs
// (experiment, campaign and fit names, --where values, file names) enters it only through
// enhanced_literal, which backslash-escapes every character enhanced mode interprets
// (^ _ @ & ~ { } and the backslash), so it prints as itself and never formats anything.
// (The SVG writer of gnuplot 5.4 copies an escaped & raw into its XML: render_plot passes it
// to the svg terminal as the octal escape \046, which that writer turns into &amp;.)
std::string enhanced_literal(const std::string& text);

// gnuplot_quote(enhanced_literal(text)): a string expression printing `text` literally in a
// title, label, key entry or tic label.
std::string gnuplot_text(const std::string& text);

// The figure formats a command writes (--figures png,svg,pdf; default png alone).
struct FigureFormats {
  bool png = true, svg = false, pdf = false;
  bool operator==(const FigureFormats&) const = default;
};
// "png", "svg,pdf", "png, svg, pdf" (any order, repeats allowed) → the set; an empty list or an
// unknown name → std::invalid_argument with a one-line message naming the accepted ones.
FigureFormats parse_figure_formats(const std::string& list);
// `figure` with its extension replaced by each chosen format's, in the order png, svg, pdf.
std::vector<std::filesystem::path> figure_files(const std::filesystem::path& figure, const FigureFormats& formats);

// A data block `$name << EOD ... EOD` with one row per entry of `rows` (values %.10g; NaN rows
// are written as blank lines, which gnuplot draws as gaps).
std::string gnuplot_block(const std::string& name, const std::vector<std::vector<double>>& rows);

// Renders `figure` (.png, .svg or .pdf: pngcairo, svg or pdfcairo, all in enhanced text) from
// `script`. PNG: W × H pixels, fonts as the script sets them. SVG and PDF are sized for a
// journal: one column (8.6 cm wide) when W ≤ 1000, two columns (17.8 cm, the multi-panel
// figures) otherwise, the height in the PNG's proportion, text in 8.5 pt (a script's own
// fonts are points too); the SVG in CSS pixels (96 per inch) so that it opens at that size.
// The script must not set the terminal or output: gnuplot writes a hidden
// temporary file of a fixed-pattern name in the same folder, which is tagged as ours (PNG) and
// renamed into place, so a failed plot never leaves a half-written figure. The whole script,
// data included, is kept next to the figure as FIGURE-STEM.gp (`gnuplot FIGURE-STEM.gp` redraws
// it: restyle it there), unless a file of that name exists that asperity did not write.
// Returns false when gnuplot is missing or fails (the script is still kept), with the reason in
// `*error` ("gnuplot not found on the PATH" or gnuplot's first error line).
bool render_plot(const std::filesystem::path& figure, const std::string& script, int width = 1200, int height = 800,
                 std::string* error = nullptr);

// render_plot in every format of `formats` (`figure`'s extension is replaced), one kept script
// FIGURE-STEM.gp redrawing them all. Returns false when any was not drawn (the first reason in
// `*error`); the others are still drawn.
bool render_figures(const std::filesystem::path& figure, const std::string& script, int width, int height,
                    const FigureFormats& formats, std::string* error = nullptr);

// The terminal line of a figure by its extension (what render_plot sets; tests read it).
std::string terminal_for(const std::filesystem::path& figure, int width, int height);
// `script` as the terminal of `figure` takes it (for SVG: \& as \046, above). For scripts
// that set their own outputs (a fit's plots.gp), after terminal_for.
std::string script_for_terminal(const std::filesystem::path& figure, const std::string& script);

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
