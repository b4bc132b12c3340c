#pragma once
// The project's CSV codec. Two kinds of file share it:
//  - numeric input tables (junctions, measured curves): a header row naming the columns (any
//    order), then one plain number per field; '#' lines are comments; blank lines only before
//    the header and at the end. Errors are InputError "FILE:LINE:COL: COLUMN: message".
//  - numeric matrices (a measured height map): rows of plain numbers, no header, every row as
//    long as the first; '#' comments and blank lines as above. Same errors.
//  - text tables we write and read back (the campaign store's points.csv and journal): fields
//    quoted as RFC 4180 when they must be.
// Numbers are written as the shortest text that reads back bit for bit (csv_number) or, where a
// file has always used it, as %.17g (format_g17 in io/numbers.hpp); either way the bytes depend
// only on the values. Rows end in '\n'.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace asperity::io {

// --- text fields --------------------------------------------------------------------------
// Quoted ("..." with "" escapes) when the field holds ',', '"' or blanks at the ends; newlines
// become spaces (one line per row, always).
std::string csv_field(std::string_view s);
// Splits one CSV line (RFC 4180 quoting). Throws std::runtime_error on an unterminated quote.
std::vector<std::string> csv_split(std::string_view line);

// --- numbers ------------------------------------------------------------------------------
// Shortest text that reads back to exactly x ("nan", "inf", "-inf" when not finite).
std::string csv_number(double x);

// --- numeric input tables -----------------------------------------------------------------
struct CsvTable {
  std::vector<std::string> columns;  // header names in file order
  int header_line = 0;               // 1-based
  std::vector<int> lines;            // 1-based line of each row
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const;  // index in `columns`, -1 when absent
};

// Reads `path` (at most kMaxCsvBytes; a UTF-8 byte-order mark is skipped), naming `display` in
// errors. Every header name must be in `allowed` (once), every name in `required` present, and
// every field a finite plain number; at least one data row.
CsvTable read_numeric_csv(const std::filesystem::path& path, const std::string& display,
                          const std::vector<std::string>& allowed, const std::vector<std::string>& required);

// --- numeric matrices ---------------------------------------------------------------------
struct CsvMatrix {
  std::size_t rows = 0, columns = 0;
  std::vector<double> values;  // row-major, rows × columns
  int first_line = 0;          // 1-based line of the first row
  std::vector<int> lines;      // 1-based line of each row ('#' comments may come between rows)
};

// Reads `path` like read_numeric_csv (same caps, comments, blank lines and number rules) as a
// matrix without a header. `name` is the column name errors give (e.g. "h_m"). A row wider than
// max_columns, more than max_rows rows, or a row of another width than the first is refused at
// its line before it is stored; so is a file with no rows.
CsvMatrix read_numeric_matrix_csv(const std::filesystem::path& path, const std::string& display,
                                  const std::string& name, std::size_t max_rows, std::size_t max_columns);

// --- text tables we write and read back (results tables: a study's table.csv, matrix.csv) ----
struct TextTable {
  std::vector<std::string> columns;            // the header's names
  std::vector<int> lines;                      // 1-based line of each row
  std::vector<std::vector<std::string>> rows;  // each as wide as the header
  // Index of `name`; InputError "DISPLAY:LINE: NAME: column missing" (line: the header's) when absent.
  std::size_t column(const std::string& name) const;
  std::string display;
  int header_line = 0;

  std::size_t size() const { return rows.size(); }
  int line(std::size_t row) const { return lines[row]; }
  // The fields by row and column name. A bad field is an InputError "DISPLAY:LINE:COL: NAME:
  // message" at the row's line and the column's place.
  const std::string& text(std::size_t row, const std::string& name) const;
  double number(std::size_t row, const std::string& name) const;  // a finite plain number
  // A number, or one that could not be measured as our writers spell it: nan (-nan), inf, -inf.
  double measured(std::size_t row, const std::string& name) const;
  std::int64_t count(std::size_t row, const std::string& name) const;  // a whole number >= 0
  bool yes_no(std::size_t row, const std::string& name) const;         // "yes" or "no"
  [[noreturn]] void fail(std::size_t row, const std::string& name, const std::string& message) const;
};

// Reads `path` (at most kMaxCsvBytes): '#' lines and blank lines skipped, the first other line the
// header, fields split by csv_split. No file: an empty table. A row of another width than the
// header, an unterminated quote, or more than max_rows rows: InputError at its line.
TextTable read_text_table(const std::filesystem::path& path, const std::string& display, std::size_t max_rows);

}  // namespace asperity::io
