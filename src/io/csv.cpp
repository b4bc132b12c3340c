#include "io/csv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"

namespace asperity::io {

std::string csv_field(std::string_view in) {
  std::string s(in);
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  const bool quote = s.find_first_of(",\"") != std::string::npos ||
                     (!s.empty() && (s.front() == ' ' || s.back() == ' ' || s.front() == '\t'));
  if (!quote) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::vector<std::string> csv_split(std::string_view line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false, in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"')
          cur += '"', ++i;
        else
          in_quotes = false;
      } else {
        cur += c;
      }
    } else if (c == '"' && cur.empty() && !quoted) {
      in_quotes = quoted = true;
    } else if (c == ',') {
      out.push_back(std::move(cur));
      cur.clear();
      quoted = false;
    } else {
      cur += c;
    }
  }
  if (in_quotes) throw std::runtime_error("unterminated quote in CSV line");
  out.push_back(std::move(cur));
  return out;
}

std::string csv_number(double x) { return format_double(x); }

int CsvTable::column(const std::string& name) const {
  auto it = std::find(columns.begin(), columns.end(), name);
  return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
}

namespace {

// Numeric fields are never quoted: split at every comma, blanks around a field ignored.
std::vector<std::string> split_plain_fields(std::string_view line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.emplace_back(
        trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

// One field as a finite plain number, or InputError at its line and column.
double field_number(const std::string& field, const std::string& display, int line_no, const std::string& name,
                    int col) {
  double x = 0;
  switch (parse_double(field, x)) {
    case NumberParse::ok:
      return x;
    case NumberParse::empty:
      throw InputError(display, line_no, name, "empty field (expected a number)", col);
    case NumberParse::has_unit:
      throw InputError(display, line_no, name, "expected a plain number in SI units, got " + quote(field), col);
    case NumberParse::not_finite:
      throw InputError(display, line_no, name, "must be a finite number, got " + quote(field), col);
    default:
      throw InputError(display, line_no, name, "expected a number, got " + quote(field), col);
  }
}

}  // namespace

CsvTable read_numeric_csv(const std::filesystem::path& path, const std::string& display,
                          const std::vector<std::string>& allowed, const std::vector<std::string>& required) {
  std::string text = read_input_file(path, display, kMaxCsvBytes);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // UTF-8 byte-order mark

  CsvTable t;
  int line_no = 0, blank_line = 0;
  std::istringstream lines(text);
  std::string raw;
  while (std::getline(lines, raw)) {
    ++line_no;
    const std::string_view line = trim(raw);
    if (line.empty()) {
      if (t.header_line && !blank_line) blank_line = line_no;
      continue;
    }
    if (line.front() == '#') continue;
    if (blank_line)
      throw InputError(display, blank_line, "", "blank line inside the data (only trailing blank lines are allowed)");
    std::vector<std::string> fields = split_plain_fields(line);
    if (!t.header_line) {
      t.header_line = line_no;
      for (std::size_t c = 0; c < fields.size(); ++c) {
        const std::string& name = fields[c];
        const int col = static_cast<int>(c) + 1;
        if (name.empty()) throw InputError(display, line_no, "", "empty column name in the header", col);
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
          throw InputError(
              display, line_no, name,
              "unknown column " + quote(name) + did_you_mean(name, allowed) + "; valid columns: " + join(allowed), col);
        if (t.column(name) >= 0) throw InputError(display, line_no, name, "duplicate column", col);
        t.columns.push_back(name);
      }
      for (const auto& r : required)
        if (t.column(r) < 0)
          throw InputError(display, line_no, r, "missing required column (header must name " + join(required) + ")");
      continue;
    }
    if (fields.size() != t.columns.size())
      throw InputError(display, line_no, "",
                       "expected " + std::to_string(t.columns.size()) + " fields (" + join(t.columns) + "), got " +
                           std::to_string(fields.size()),
                       static_cast<int>(std::min(fields.size(), t.columns.size())) + 1);
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c)
      row[c] = field_number(fields[c], display, line_no, t.columns[c], static_cast<int>(c) + 1);
    t.rows.push_back(std::move(row));
    t.lines.push_back(line_no);
  }
  if (!t.header_line)
    throw InputError(display, std::max(line_no, 1), required.empty() ? "" : required.front(),
                     "missing header row (expected columns " + join(allowed) + ")");
  if (t.rows.empty())
    throw InputError(display, t.header_line, required.empty() ? "" : required.front(), "no data rows after the header");
  return t;
}

CsvMatrix read_numeric_matrix_csv(const std::filesystem::path& path, const std::string& display,
                                  const std::string& name, std::size_t max_rows, std::size_t max_columns) {
  std::string text = read_input_file(path, display, kMaxCsvBytes);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // UTF-8 byte-order mark

  CsvMatrix m;
  int line_no = 0, blank_line = 0;
  std::size_t start = 0;
  // Line by line over the text in place: the matrix may be most of the file's size.
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line = trim(std::string_view(text).substr(start, end - start));
    start = end + 1;
    ++line_no;
    if (line.empty()) {
      if (m.rows && !blank_line) blank_line = line_no;
      continue;
    }
    if (line.front() == '#') continue;
    if (blank_line)
      throw InputError(display, blank_line, "", "blank line inside the data (only trailing blank lines are allowed)");
    const std::vector<std::string> fields = split_plain_fields(line);
    if (!m.rows) {
      if (fields.size() > max_columns)
        throw InputError(display, line_no, name,
                         "row of " + std::to_string(fields.size()) + " values, more than the " +
                             std::to_string(max_columns) + " allowed",
                         static_cast<int>(max_columns) + 1);
      m.columns = fields.size();
      m.first_line = line_no;
    } else if (fields.size() != m.columns) {
      throw InputError(display, line_no, name,
                       "expected " + std::to_string(m.columns) + " values (as in the first row, line " +
                           std::to_string(m.first_line) + "), got " + std::to_string(fields.size()),
                       static_cast<int>(std::min(fields.size(), m.columns)) + 1);
    }
    if (m.rows == max_rows)
      throw InputError(display, line_no, name, "more than the " + std::to_string(max_rows) + " rows allowed");
    for (std::size_t c = 0; c < fields.size(); ++c)
      m.values.push_back(field_number(fields[c], display, line_no, name, static_cast<int>(c) + 1));
    m.lines.push_back(line_no);
    ++m.rows;
  }
  if (!m.rows) throw InputError(display, std::max(line_no, 1), name, "no rows of numbers");
  return m;
}

std::size_t TextTable::column(const std::string& name) const {
  const auto it = std::find(columns.begin(), columns.end(), name);
  if (it == columns.end()) throw InputError(display, header_line, name, "column missing");
  return static_cast<std::size_t>(it - columns.begin());
}

const std::string& TextTable::text(std::size_t row, const std::string& name) const { return rows[row][column(name)]; }

void TextTable::fail(std::size_t row, const std::string& name, const std::string& message) const {
  throw InputError(display, lines[row], name, message, static_cast<int>(column(name)) + 1);
}

double TextTable::number(std::size_t row, const std::string& name) const {
  const std::string& s = text(row, name);
  double x = 0;
  switch (parse_double(s, x)) {
    case NumberParse::ok:
      return x;
    case NumberParse::empty:
      fail(row, name, "empty field (expected a number)");
    case NumberParse::not_finite:
      fail(row, name, "must be a finite number, got " + quote(s));
    default:
      fail(row, name, "expected a number, got " + quote(s));
  }
}

double TextTable::measured(std::size_t row, const std::string& name) const {
  const std::string_view s = trim(text(row, name));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  if (s == "nan") return nan;
  if (s == "-nan") return std::copysign(nan, -1.0);  // printf's spelling of a NaN with its sign bit set
  if (s == "inf") return inf;
  if (s == "-inf") return -inf;
  return number(row, name);
}

std::int64_t TextTable::count(std::size_t row, const std::string& name) const {
  const std::string_view s = trim(text(row, name));
  std::int64_t n = -1;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), n);
  if (s.empty() || r.ec != std::errc() || r.ptr != s.data() + s.size() || n < 0)
    fail(row, name, "expected a whole number >= 0, got " + quote(text(row, name)));
  return n;
}

bool TextTable::yes_no(std::size_t row, const std::string& name) const {
  const std::string& s = text(row, name);
  if (s == "yes") return true;
  if (s == "no") return false;
  fail(row, name, "expected yes or no, got " + quote(s));
}

TextTable read_text_table(const std::filesystem::path& path, const std::string& display, std::size_t max_rows) {
  TextTable t;
  t.display = display;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return t;
  std::istringstream in(read_input_file(path, display, kMaxCsvBytes));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    try {
      f = csv_split(line);
    } catch (const std::runtime_error& e) {
      throw InputError(display, n, "", e.what());
    }
    if (t.columns.empty()) {
      t.columns = std::move(f);
      t.header_line = n;
      continue;
    }
    if (t.rows.size() >= max_rows) throw InputError(display, n, "", "more than " + std::to_string(max_rows) + " rows");
    if (f.size() != t.columns.size())
      throw InputError(display, n, "",
                       std::to_string(f.size()) + " fields where the header has " + std::to_string(t.columns.size()));
    t.rows.push_back(std::move(f));
    t.lines.push_back(n);
  }
  return t;
}

}  // namespace asperity::io
