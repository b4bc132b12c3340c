#include "scene/csv.hpp"

#include <cmath>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"

namespace asperity {

using io::format_double;

std::string junction_area_problem(double a) {
  // 1e-20 m² (0.01 nm², below one atom) to 1 m²: outside it the contact law has no meaning,
  // and A0^(p+1), slip distances and time scales leave the range of double.
  if (a >= 1e-20 && a <= 1.0) return "";
  return "junction area must be in [1e-20, 1] m^2, got " + format_double(a);
}

std::string junction_coordinate_problem(double v) {
  if (std::abs(v) <= kMaxJunctionCoordinate_m) return "";
  return "junction centre must be within +-" + format_double(kMaxJunctionCoordinate_m) + " m, got " + format_double(v);
}

std::string measured_force_problem(double q) { return q >= 0 ? "" : "force must be >= 0, got " + format_double(q); }
std::string measured_area_problem(double a) { return a > 0 ? "" : "area must be > 0, got " + format_double(a); }

JunctionPopulation read_junctions_csv(const std::filesystem::path& csv, const std::string& display) {
  std::vector<int> lines;
  return read_junctions_csv(csv, display, lines);
}

JunctionPopulation read_junctions_csv(const std::filesystem::path& csv, const std::string& display,
                                      std::vector<int>& lines) {
  const io::CsvTable t = io::read_numeric_csv(csv, display, {"area_m2", "x_m", "y_m"}, {"area_m2"});
  lines = t.lines;
  const int ca = t.column("area_m2"), cx = t.column("x_m"), cy = t.column("y_m");
  if ((cx < 0) != (cy < 0)) {
    const std::string missing = cx < 0 ? "x_m" : "y_m";
    throw io::InputError(display, t.header_line, missing, "x_m and y_m must be given together (or neither)");
  }
  JunctionPopulation p;
  p.area_m2.reserve(t.rows.size());
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double a = t.rows[i][static_cast<std::size_t>(ca)];
    if (const std::string why = junction_area_problem(a); !why.empty())
      throw io::InputError(display, t.lines[i], "area_m2", why, ca + 1);
    p.area_m2.push_back(a);
    if (cx >= 0) {
      for (const int c : {cx, cy}) {
        const double v = t.rows[i][static_cast<std::size_t>(c)];
        if (const std::string why = junction_coordinate_problem(v); !why.empty())
          throw io::InputError(display, t.lines[i], t.columns[static_cast<std::size_t>(c)], why, c + 1);
      }
      p.x_m.push_back(t.rows[i][static_cast<std::size_t>(cx)]);
      p.y_m.push_back(t.rows[i][static_cast<std::size_t>(cy)]);
    }
  }
  return p;
}

MeasuredCurve read_measured_csv(const std::filesystem::path& csv, const std::string& display) {
  const io::CsvTable t = io::read_numeric_csv(csv, display, {"Q_N", "A_m2"}, {"Q_N", "A_m2"});
  const int cq = t.column("Q_N"), ca = t.column("A_m2");
  MeasuredCurve m;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double q = t.rows[i][static_cast<std::size_t>(cq)], a = t.rows[i][static_cast<std::size_t>(ca)];
    if (const std::string why = measured_force_problem(q); !why.empty())
      throw io::InputError(display, t.lines[i], "Q_N", why, cq + 1);
    if (const std::string why = measured_area_problem(a); !why.empty())
      throw io::InputError(display, t.lines[i], "A_m2", why, ca + 1);
    m.Q_N.push_back(q);
    m.A_m2.push_back(a);
  }
  return m;
}

MeasuredForce read_force_csv(const std::filesystem::path& csv, const std::string& display) {
  const io::CsvTable t = io::read_numeric_csv(csv, display, {"t_s", "Q_N"}, {"t_s", "Q_N"});
  const int ct = t.column("t_s"), cq = t.column("Q_N");
  MeasuredForce f;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double time = t.rows[i][static_cast<std::size_t>(ct)], q = t.rows[i][static_cast<std::size_t>(cq)];
    if (!(time >= 0))
      throw io::InputError(display, t.lines[i], "t_s", "time must be >= 0, got " + format_double(time), ct + 1);
    if (!f.t_s.empty() && !(time > f.t_s.back()))
      throw io::InputError(display, t.lines[i], "t_s",
                           "times must increase strictly: " + format_double(time) + " after " +
                               format_double(f.t_s.back()) + " (line " + std::to_string(t.lines[i - 1]) + ")",
                           ct + 1);
    f.t_s.push_back(time);
    f.Q_N.push_back(q);
  }
  if (f.t_s.size() < 2)
    throw io::InputError(display, t.header_line, "t_s",
                         "a force history needs at least 2 samples, got " + std::to_string(f.t_s.size()));
  return f;
}

MeasuredForce read_force_csv(const std::filesystem::path& csv) { return read_force_csv(csv, io::input_path(csv)); }

JunctionPopulation read_junctions_csv(const std::filesystem::path& csv) {
  return read_junctions_csv(csv, io::input_path(csv));
}

MeasuredCurve read_measured_csv(const std::filesystem::path& csv) {
  return read_measured_csv(csv, io::input_path(csv));
}

void write_junctions_csv(const std::filesystem::path& csv, const JunctionPopulation& j) {
  const bool xy = !j.x_m.empty() || !j.y_m.empty();
  if (xy && (j.x_m.size() != j.size() || j.y_m.size() != j.size()))
    throw std::invalid_argument("write_junctions_csv: x_m/y_m must be empty or as long as area_m2");
  std::string s = xy ? "area_m2,x_m,y_m\n" : "area_m2\n";
  for (std::size_t i = 0; i < j.size(); ++i) {
    s += io::csv_number(j.area_m2[i]);
    if (xy) {
      s += ',';
      s += io::csv_number(j.x_m[i]);
      s += ',';
      s += io::csv_number(j.y_m[i]);
    }
    s += '\n';
  }
  io::write_text_file(csv, s);
}

void write_measured_csv(const std::filesystem::path& csv, const MeasuredCurve& m) {
  if (m.Q_N.size() != m.A_m2.size()) throw std::invalid_argument("write_measured_csv: Q_N and A_m2 differ in length");
  std::string s = "Q_N,A_m2\n";
  for (std::size_t i = 0; i < m.Q_N.size(); ++i) {
    s += io::csv_number(m.Q_N[i]);
    s += ',';
    s += io::csv_number(m.A_m2[i]);
    s += '\n';
  }
  io::write_text_file(csv, s);
}

void write_force_csv(const std::filesystem::path& csv, const MeasuredForce& f,
                     const std::vector<std::string>& comment) {
  if (f.t_s.size() != f.Q_N.size()) throw std::invalid_argument("write_force_csv: t_s and Q_N differ in length");
  std::string s;
  for (const std::string& line : comment) s += "# " + line + "\n";
  s += "t_s,Q_N\n";
  for (std::size_t i = 0; i < f.t_s.size(); ++i) {
    s += io::csv_number(f.t_s[i]);
    s += ',';
    s += io::csv_number(f.Q_N[i]);
    s += '\n';
  }
  io::write_text_file(csv, s);
}

}  // namespace asperity
