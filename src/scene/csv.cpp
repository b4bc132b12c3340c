#include "scene/csv.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"

namespace asperity {

using namespace scene_io;

namespace {

struct Table {
  std::vector<std::string> columns;  // header names in file order
  int header_line = 0;
  std::vector<int> lines;            // 1-based line of each row
  std::vector<std::vector<double>> rows;
  int column(const std::string& name) const {
    auto it = std::find(columns.begin(), columns.end(), name);
    return it == columns.end() ? -1 : static_cast<int>(it - columns.begin());
  }
};

std::vector<std::string> split_fields(std::string_view line) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    out.emplace_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

Table read_table(const std::filesystem::path& path, const std::string& display,
                 const std::vector<std::string>& allowed, const std::vector<std::string>& required) {
  std::string text = read_input_file(path, display, kMaxCsvBytes);
  if (text.rfind("\xEF\xBB\xBF", 0) == 0) text.erase(0, 3);  // UTF-8 byte-order mark

  Table t;
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
    std::vector<std::string> fields = split_fields(line);
    if (!t.header_line) {
      t.header_line = line_no;
      for (std::size_t c = 0; c < fields.size(); ++c) {
        const std::string& name = fields[c];
        const int col = static_cast<int>(c) + 1;
        if (name.empty()) throw InputError(display, line_no, "", "empty column name in the header", col);
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
          throw InputError(display, line_no, name,
                           "unknown column " + quote(name) + scene_io::did_you_mean(name, allowed) +
                               "; valid columns: " + scene_io::join(allowed),
                           col);
        if (t.column(name) >= 0) throw InputError(display, line_no, name, "duplicate column", col);
        t.columns.push_back(name);
      }
      for (const auto& r : required)
        if (t.column(r) < 0)
          throw InputError(display, line_no, r, "missing required column (header must name " + scene_io::join(required) + ")");
      continue;
    }
    if (fields.size() != t.columns.size())
      throw InputError(display, line_no, "",
                       "expected " + std::to_string(t.columns.size()) + " fields (" + scene_io::join(t.columns) +
                           "), got " + std::to_string(fields.size()),
                       static_cast<int>(std::min(fields.size(), t.columns.size())) + 1);
    std::vector<double> row(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c) {
      const int col = static_cast<int>(c) + 1;
      switch (parse_double(fields[c], row[c])) {
        case NumberParse::ok:
          break;
        case NumberParse::empty:
          throw InputError(display, line_no, t.columns[c], "empty field (expected a number)", col);
        case NumberParse::has_unit:
          throw InputError(display, line_no, t.columns[c],
                           "expected a plain number in SI units, got " + quote(fields[c]), col);
        case NumberParse::not_finite:
          throw InputError(display, line_no, t.columns[c], "must be a finite number, got " + quote(fields[c]), col);
        default:
          throw InputError(display, line_no, t.columns[c], "expected a number, got " + quote(fields[c]), col);
      }
    }
    t.rows.push_back(std::move(row));
    t.lines.push_back(line_no);
  }
  if (!t.header_line)
    throw InputError(display, std::max(line_no, 1), required.empty() ? "" : required.front(),
                     "missing header row (expected columns " + scene_io::join(allowed) + ")");
  if (t.rows.empty())
    throw InputError(display, t.header_line, required.empty() ? "" : required.front(), "no data rows after the header");
  return t;
}

}  // namespace

namespace scene_io {

JunctionPopulation read_junctions_csv(const std::filesystem::path& csv, const std::string& display) {
  const Table t = read_table(csv, display, {"area_m2", "x_m", "y_m"}, {"area_m2"});
  const int ca = t.column("area_m2"), cx = t.column("x_m"), cy = t.column("y_m");
  if ((cx < 0) != (cy < 0)) {
    const std::string missing = cx < 0 ? "x_m" : "y_m";
    throw InputError(display, t.header_line, missing, "x_m and y_m must be given together (or neither)");
  }
  JunctionPopulation p;
  p.area_m2.reserve(t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double a = t.rows[i][static_cast<std::size_t>(ca)];
    // 1e-20 m² (0.01 nm², below one atom) to 1 m²: outside it the contact law has no meaning,
    // and A0^(p+1), slip distances and time scales leave the range of double.
    if (!(a >= 1e-20 && a <= 1.0))
      throw InputError(display, t.lines[i], "area_m2", "junction area must be in [1e-20, 1] m^2, got " + format_double(a), ca + 1);
    p.area_m2.push_back(a);
    if (cx >= 0) {
      p.x_m.push_back(t.rows[i][static_cast<std::size_t>(cx)]);
      p.y_m.push_back(t.rows[i][static_cast<std::size_t>(cy)]);
    }
  }
  return p;
}

MeasuredCurve read_measured_csv(const std::filesystem::path& csv, const std::string& display) {
  const Table t = read_table(csv, display, {"Q_N", "A_m2"}, {"Q_N", "A_m2"});
  const int cq = t.column("Q_N"), ca = t.column("A_m2");
  MeasuredCurve m;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double q = t.rows[i][static_cast<std::size_t>(cq)], a = t.rows[i][static_cast<std::size_t>(ca)];
    if (!(q >= 0)) throw InputError(display, t.lines[i], "Q_N", "force must be >= 0, got " + format_double(q), cq + 1);
    if (!(a > 0)) throw InputError(display, t.lines[i], "A_m2", "area must be > 0, got " + format_double(a), ca + 1);
    m.Q_N.push_back(q);
    m.A_m2.push_back(a);
  }
  return m;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error("cannot write " + path.string());
  }
}

}  // namespace scene_io

JunctionPopulation read_junctions_csv(const std::filesystem::path& csv) {
  return scene_io::read_junctions_csv(csv, csv.lexically_normal().string());
}

MeasuredCurve read_measured_csv(const std::filesystem::path& csv) {
  return scene_io::read_measured_csv(csv, csv.lexically_normal().string());
}

void write_junctions_csv(const std::filesystem::path& csv, const JunctionPopulation& j) {
  const bool xy = !j.x_m.empty() || !j.y_m.empty();
  if (xy && (j.x_m.size() != j.size() || j.y_m.size() != j.size()))
    throw std::invalid_argument("write_junctions_csv: x_m/y_m must be empty or as long as area_m2");
  std::string s = xy ? "area_m2,x_m,y_m\n" : "area_m2\n";
  for (std::size_t i = 0; i < j.size(); ++i) {
    s += format_double(j.area_m2[i]);
    if (xy) {
      s += ',';
      s += format_double(j.x_m[i]);
      s += ',';
      s += format_double(j.y_m[i]);
    }
    s += '\n';
  }
  scene_io::write_text_file(csv, s);
}

void write_measured_csv(const std::filesystem::path& csv, const MeasuredCurve& m) {
  if (m.Q_N.size() != m.A_m2.size())
    throw std::invalid_argument("write_measured_csv: Q_N and A_m2 differ in length");
  std::string s = "Q_N,A_m2\n";
  for (std::size_t i = 0; i < m.Q_N.size(); ++i) {
    s += format_double(m.Q_N[i]);
    s += ',';
    s += format_double(m.A_m2[i]);
    s += '\n';
  }
  scene_io::write_text_file(csv, s);
}

}  // namespace asperity
