#include "bench/read_back.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

#include "io/input_error.hpp"
#include "io/numbers.hpp"

namespace asperity {
namespace fs = std::filesystem;

BenchCsv::BenchCsv(const fs::path& file, const std::string& command, std::size_t max_rows) {
  const std::string display = io::input_path(file);
  std::error_code ec;
  // read_text_table reads a missing file as an empty table (a store not yet written); here the
  // bench must have written it.
  if (!fs::exists(file, ec)) throw io::InputError(display, 0, "", "file not found (written by `" + command + "`)");
  table_ = io::read_text_table(file, display, max_rows);
  if (table_.rows.empty())
    throw io::InputError(display, table_.header_line, "", "no data rows (written by `" + command + "`)");
}

const std::string& BenchCsv::text(std::size_t row, const std::string& column) const {
  return table_.rows[row][table_.column(column)];
}

void BenchCsv::fail(std::size_t row, const std::string& column, const std::string& message) const {
  throw io::InputError(table_.display, table_.lines[row], column, message, static_cast<int>(table_.column(column)) + 1);
}

double BenchCsv::number(std::size_t row, const std::string& column) const {
  const std::string& s = text(row, column);
  double x = 0;
  switch (io::parse_double(s, x)) {
    case io::NumberParse::ok:
      return x;
    case io::NumberParse::empty:
      fail(row, column, "empty field (expected a number)");
    case io::NumberParse::not_finite:
      fail(row, column, "must be a finite number, got " + io::quote(s));
    default:
      fail(row, column, "expected a number, got " + io::quote(s));
  }
}

double BenchCsv::measured(std::size_t row, const std::string& column) const {
  const std::string_view s = io::trim(text(row, column));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  if (s == "nan") return nan;
  if (s == "-nan") return std::copysign(nan, -1.0);  // printf's spelling of a NaN with its sign bit set
  if (s == "inf") return inf;
  if (s == "-inf") return -inf;
  return number(row, column);
}

std::int64_t BenchCsv::count(std::size_t row, const std::string& column) const {
  const std::string_view s = io::trim(text(row, column));
  std::int64_t n = -1;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), n);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || n < 0)
    fail(row, column, "expected a whole number >= 0, got " + io::quote(text(row, column)));
  return n;
}

bool BenchCsv::yes_no(std::size_t row, const std::string& column) const {
  const std::string& s = text(row, column);
  if (s == "yes") return true;
  if (s == "no") return false;
  fail(row, column, "expected yes or no, got " + io::quote(s));
}

void check_redraw_targets(const fs::path& figure, const FigureFormats& formats) {
  std::error_code ec;
  for (const fs::path& f : figure_files(figure, formats))
    if (fs::exists(fs::symlink_status(f, ec)) && !png_is_ours(f))
      throw io::InputError(io::input_path(f), 0, "", "refusing to replace a file that asperity did not draw");
}

}  // namespace asperity
