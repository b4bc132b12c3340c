#pragma once
// Reading back a CSV a bench wrote (savings.csv, work_precision.csv) with the project's text
// table reader (io/csv.hpp read_text_table), each field by its column's name as the writer
// printed it, for `asperity bench savings|tradeoff --redraw`. A bad field is an InputError
// "FILE:LINE:COL: COLUMN: message"; a missing column "FILE:LINE: COLUMN: column missing" (the
// header's line).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

#include "io/csv.hpp"
#include "report/gnuplot.hpp"  // FigureFormats

namespace asperity {

class BenchCsv {
 public:
  // Reads `file`; `command` (e.g. "asperity bench savings") names what writes it when the file
  // is missing. No data row, a row of another width than the header, more than `max_rows`
  // rows: InputError.
  BenchCsv(const std::filesystem::path& file, const std::string& command, std::size_t max_rows = 100000);

  std::size_t size() const { return table_.rows.size(); }
  int line(std::size_t row) const { return table_.lines[row]; }  // 1-based
  const std::string& display() const { return table_.display; }

  const std::string& text(std::size_t row, const std::string& column) const;
  // A finite plain number.
  double number(std::size_t row, const std::string& column) const;
  // A number, or one that could not be measured as the writers spell it: nan (or -nan), inf, -inf.
  double measured(std::size_t row, const std::string& column) const;
  // A whole number >= 0 (counts: steps, bytes, repeats).
  std::int64_t count(std::size_t row, const std::string& column) const;
  // "yes" or "no".
  bool yes_no(std::size_t row, const std::string& column) const;

  // InputError at the row's line and the column's place.
  [[noreturn]] void fail(std::size_t row, const std::string& column, const std::string& message) const;

 private:
  io::TextTable table_;
};

// Before a redraw replaces `figure` in each of `formats`: an existing file that asperity did not
// draw (report/gnuplot.hpp png_is_ours) is refused (InputError naming it).
void check_redraw_targets(const std::filesystem::path& figure, const FigureFormats& formats);

}  // namespace asperity
