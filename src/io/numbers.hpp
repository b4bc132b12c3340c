#pragma once
// Exact, strict number text for scene files and CSVs (no locale, no units, no NaN/inf).
#include <string>
#include <string_view>

namespace asperity::io {

// Shortest text that reads back to exactly x (std::to_chars), e.g. 0.1 → "0.1", 7.25e-16.
std::string format_double(double x);

// format_double, or "nan", "inf", "-inf" when not finite: a store row keeps a failed value.
std::string format_exact(double x);

// format_double for a scene file, which has no spelling for NaN or infinity: throws
// std::invalid_argument when x is not finite.
std::string format_scene_number(double x);

// %.17g: round-trips too, in the longer spelling series.csv, summary.yaml and the fit tables
// have always used (their bytes must not change); "nan"/"inf" when not finite.
std::string format_g17(double x);

// x through a printf format with one double conversion ("%g", "%.3g", "%.4g"), for report text.
std::string format_printf(const char* format, double x);

// format_printf, or "–" when x is not finite: a report table's cell with no value.
std::string format_cell(const char* format, double x);

// %.<digits>g: `digits` significant digits for text meant to be read (printf's %g is 6).
std::string format_significant(double x, int digits = 6);

// Three significant digits for derived values in messages, e.g. 1.5e+07, 0.000209.
std::string format_short(double x);

// A count as a whole number ("%.0f") when it is one, else three significant digits ("%.3g").
std::string format_count(double x);

enum class NumberParse { ok, empty, not_a_number, has_unit, not_finite };

// Parses all of `text` (surrounding blanks ignored, optional leading '+') as a finite double.
// has_unit: a number followed by a word ("1.6 MPa"); not_finite: nan/inf/.inf or overflow.
NumberParse parse_double(std::string_view text, double& out);

// Strict integer (no fraction, no exponent).
bool parse_int(std::string_view text, int& out);

std::string_view trim(std::string_view s);

// Value text for messages: single line, at most ~40 characters, in single quotes.
std::string quote(std::string_view s);

// True when `s` holds a control character (a byte below 0x20, e.g. newline or tab, or 0x7f).
// Names (experiments, campaigns, grids) must not: they become table rows, folder names and plot
// titles, where a line break would split a row or end a command.
inline bool has_control_char(std::string_view s) {
  for (const char c : s)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  return false;
}

}  // namespace asperity::io
