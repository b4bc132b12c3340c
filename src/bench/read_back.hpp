#pragma once
// Reading back a CSV a bench wrote (savings.csv, work_precision.csv) with the project's text
// table reader (io/csv.hpp read_text_table), each field by its column's name as the writer
// printed it, for `asperity bench savings|tradeoff --redraw`. A bad field is an InputError
// "FILE:LINE:COL: COLUMN: message"; a missing column "FILE:LINE: COLUMN: column missing" (the
// header's line).
#include <cstddef>
#include <filesystem>
#include <string>

#include "io/csv.hpp"
#include "report/gnuplot.hpp"  // FigureFormats

namespace asperity {

// Reads `file` with io::read_text_table (the fields then read by name: TextTable::number, count,
// measured, yes_no); `command` (e.g. "asperity bench savings") names what writes it when the file
// is missing. No data row, a row of another width than the header, more than `max_rows` rows:
// InputError.
io::TextTable read_bench_csv(const std::filesystem::path& file, const std::string& command,
                             std::size_t max_rows = 100000);

// The `repeats` column of `row`: over how many runs each time was measured, a whole number in
// [1, INT_MAX] (InputError at its place otherwise).
int read_repeats(const io::TextTable& table, std::size_t row);

// Before a redraw replaces `figure` in each of `formats`: an existing file that asperity did not
// draw (report/gnuplot.hpp png_is_ours) is refused (InputError naming it).
void check_redraw_targets(const std::filesystem::path& figure, const FigureFormats& formats);

}  // namespace asperity
