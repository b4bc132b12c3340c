#include "report/plot_axes.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <system_error>

#include "campaign/store.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "report/gnuplot.hpp"
#include "report/units.hpp"

namespace asperity::plot_detail {
namespace fs = std::filesystem;

bool number_of(const std::string& s, double& x) {
  if (s == "nan" || s == "inf" || s == "-inf") {
    x = s == "nan" ? NAN : (s == "inf" ? INFINITY : -INFINITY);
    return true;
  }
  return io::parse_double(s, x) == io::NumberParse::ok;
}

bool same_value(const std::string& a, const std::string& b) {
  double x = 0, y = 0;
  if (a == b) return true;
  return number_of(a, x) && number_of(b, y) && x == y;
}

std::string file_part(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '_';
  return s;
}

// Sorted distinct values of a column (numerically), as their store texts.
std::vector<std::string> distinct_sorted(const std::vector<std::vector<std::string>>& rows, std::size_t col) {
  std::map<double, std::string> m;
  for (const auto& r : rows) {
    double v = 0;
    number_of(r[col], v);
    m.emplace(v, r[col]);
  }
  std::vector<std::string> out;
  for (const auto& [v, t] : m) out.push_back(t);
  return out;
}

// The PNG a plot may write: --out must name a .png file; an existing file is replaced only when
// render_png wrote it (a PNG tagged as ours) or, inside the store folder (asperity's own), when
// it is a PNG (heat maps drawn before the tag existed, e.g. the committed ones).
void check_png_target(const fs::path& png, const fs::path& store, bool from_out) {
  const std::string ext = png.extension().string();
  if (from_out && ext != ".png" && ext != ".svg" && ext != ".pdf")
    throw io::InputError(png.string(), 0, "--out",
                         "must name a .png, .svg or .pdf file (a plot never writes other files)");
  std::error_code ec;
  const auto st = fs::symlink_status(png, ec);
  if (!fs::exists(st) || png_is_ours(png)) return;
  const fs::path folder = png.parent_path().empty() ? fs::path(".") : png.parent_path();
  if (fs::is_regular_file(st) && fs::equivalent(folder, store, ec)) {
    char head[8] = {};
    std::ifstream(png, std::ios::binary).read(head, sizeof head);
    if (std::string(head, sizeof head) == std::string("\x89PNG\r\n\x1a\n", 8)) return;
  }
  throw io::InputError(
      png.string(), 0, from_out ? "--out" : "plot",
      "refusing to replace a file asperity did not write (only figures drawn by asperity are replaced); "
      "choose a new name");
}

std::string keep_grids_varying(std::vector<std::vector<std::string>>& rows, std::size_t grid_column,
                               const std::vector<std::size_t>& columns) {
  std::map<std::string, std::vector<std::set<std::string>>> seen;
  for (const auto& r : rows) {
    auto& sets = seen[r[grid_column]];
    sets.resize(columns.size());
    for (std::size_t k = 0; k < columns.size(); ++k) sets[k].insert(r[columns[k]]);
  }
  std::set<std::string> varying;
  for (const auto& [g, sets] : seen)
    if (std::all_of(sets.begin(), sets.end(), [](const auto& s) { return s.size() > 1; })) varying.insert(g);
  std::string used;
  if (varying.empty() || varying.size() == seen.size()) return used;
  std::erase_if(rows, [&](const auto& r) { return !varying.count(r[grid_column]); });
  for (const auto& g : varying) used += (used.empty() ? "" : ",") + g;
  return used;
}

bool store_is_stand_in(const fs::path& store) {
  return io::read_file_text(store / "provenance.yaml").find("stand_in_data: true") != std::string::npos;
}

std::string where_title(const std::vector<std::string>& where) {
  std::string title;
  for (const std::string& w : where) {
    const std::size_t eq = w.find('=');
    const std::string column = eq == std::string::npos ? w : w.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : w.substr(eq + 1);
    if (column == "grid") continue;
    if (column == "experiment")
      title += ", " + enhanced_literal(value);
    else if (has_column_symbol(column))
      title += ", " + column_symbol(column) + " = " + enhanced_literal(value);
    else
      title += ", " + enhanced_literal(w);
  }
  return title;
}

// Whether an axis reads better on a log scale: positive values that are geometrically spaced
// (three or more, equal ratios to 1e-6 and not equally spaced, as `logspace` makes them) or
// that span two decades or more (e.g. c_min ∈ {1e-5, 1e-2}).
bool log_axis(const std::vector<double>& v) {
  if (v.size() < 2 || v.front() <= 0) return false;
  if (v.back() / v.front() >= 100) return true;
  if (v.size() < 3) return false;
  const double r = v[1] / v[0], d = v[1] - v[0];
  bool geometric = r > 1, arithmetic = true;
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    geometric = geometric && std::abs(v[i + 1] / v[i] / r - 1) < 1e-6;
    arithmetic = arithmetic && std::abs((v[i + 1] - v[i]) / d - 1) < 1e-6;
  }
  return geometric && !arithmetic;
}

// Cell edges around sorted distinct values: midpoints between neighbours (in log10 on a log
// axis), the outer cells as wide as their neighbour's half gap (±0.5, or ±0.5 decade, alone).
std::vector<std::pair<double, double>> cell_edges(const std::vector<double>& v, bool log) {
  const std::size_t n = v.size();
  std::vector<double> u(n);
  for (std::size_t i = 0; i < n; ++i) u[i] = log ? std::log10(v[i]) : v[i];
  std::vector<std::pair<double, double>> e(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double left = i > 0 ? 0.5 * (u[i] - u[i - 1]) : (n > 1 ? 0.5 * (u[1] - u[0]) : 0.5);
    const double right = i + 1 < n ? 0.5 * (u[i + 1] - u[i]) : (n > 1 ? 0.5 * (u[n - 1] - u[n - 2]) : 0.5);
    e[i] = {u[i] - left, u[i] + right};
    if (log) e[i] = {std::pow(10.0, e[i].first), std::pow(10.0, e[i].second)};
  }
  return e;
}

namespace {

// Which of the tic labels `labels` at the sorted values `v` to print so that none overlaps the
// last one printed: at one journal column's width a heat map's or line plot's x axis holds about
// 28 characters and its y axis about 10 lines of tic text. A label needs its half width on either
// side plus one character (x; two characters in all when rotated) or one and a half lines (y).
std::vector<bool> labels_that_fit(const std::vector<double>& v, const std::vector<std::string>& labels,
                                  std::pair<double, double> range, bool log, bool x, bool rotated) {
  const auto at = [&](double value) { return log ? std::log10(value) : value; };
  const double lo = at(range.first), span = at(range.second) - lo, length = x ? 28.0 : 10.0;
  std::vector<bool> keep(v.size(), true);
  if (!(span > 0)) return keep;
  const auto size = [&](std::size_t i) { return !x ? 1.0 : (rotated ? 1.0 : static_cast<double>(labels[i].size())); };
  double last_at = 0, last_size = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const double p = (at(v[i]) - lo) / span * length;
    keep[i] = i == 0 || p - last_at >= 0.5 * (last_size + size(i)) + (x ? 1.0 : 0.5);
    if (keep[i]) last_at = p, last_size = size(i);
  }
  return keep;
}

}  // namespace

// The axis settings of a numeric axis: its label with unit, log scale when it reads better,
// tics at the values themselves (their store texts) when there are few, labelled where the
// labels fit a journal column (more than eight x labels rotated), the range of the cells.
std::string axis_settings(const char* axis, const std::string& column, const std::vector<std::string>& texts,
                          const std::vector<std::pair<double, double>>& edges, bool log) {
  const bool x = axis[0] == 'x', rotated = x && texts.size() > 8;  // many x labels: rotated
  std::ostringstream gp;
  gp << "set " << axis << "label " << gnuplot_quote(axis_markup(column)) << "\n";
  if (log) gp << "set logscale " << axis << "\n";
  if (!texts.empty() && texts.size() <= 12) {
    const double scale = figure_unit(column).scale;
    std::vector<double> v(texts.size());
    std::vector<std::string> labels(texts.size());
    for (std::size_t i = 0; i < texts.size(); ++i) {
      number_of(texts[i], v[i]);
      v[i] *= scale;
      labels[i] = io::format_short(v[i]);  // to 6 digits (the store's exact texts can be 17); positions exact
    }
    const auto range =
        edges.empty() ? std::pair{v.front(), v.back()} : std::pair{edges.front().first, edges.back().second};
    const std::vector<bool> keep = labels_that_fit(v, labels, range, log, x, rotated);
    gp << "set " << axis << "tics (";
    for (std::size_t i = 0; i < texts.size(); ++i)
      gp << (i ? ", " : "") << gnuplot_text(keep[i] ? labels[i] : "") << " " << io::format_double(v[i]);
    gp << ")\n";
  }
  if (rotated) gp << "set xtics rotate by 60 right\n";
  if (!edges.empty())
    gp << "set " << axis << "range [" << io::format_double(edges.front().first) << ":"
       << io::format_double(edges.back().second) << "]\n";
  return gp.str();
}

StoreTable::StoreTable(const fs::path& dir, const std::vector<std::string>& where) : store(dir) {
  const StoreReader s(dir);
  header = s.header();
  cols = io::csv_split(header);
  std::vector<std::pair<std::size_t, std::string>> filters;
  for (const std::string& w : where) {
    const std::size_t eq = w.find('=');
    if (eq == std::string::npos)
      throw io::InputError("asperity plot", 0, "--where", "expected column=value, got '" + w + "'");
    filters.emplace_back(column(w.substr(0, eq), "--where"), w.substr(eq + 1));
  }
  for (const StoredRow& stored : s.rows()) {
    auto r = io::csv_split(s.row(stored));
    if (r.size() != cols.size()) continue;
    bool keep = true;
    for (const auto& [c, v] : filters) keep = keep && same_value(r[c], v);
    if (keep) rows.push_back(std::move(r));
  }
}

std::size_t StoreTable::column(const std::string& name, const char* option) const {
  const auto it = std::find(cols.begin(), cols.end(), name);
  if (it == cols.end())
    throw io::InputError("asperity plot", 0, option,
                         "no column '" + name + "' in the store " + store.string() + "; columns: " + header);
  return static_cast<std::size_t>(it - cols.begin());
}

std::vector<std::vector<std::string>> StoreTable::rows_with_numbers(const std::vector<std::size_t>& numeric) const {
  std::vector<std::vector<std::string>> out;
  for (const auto& r : rows) {
    bool ok = true;
    for (const std::size_t c : numeric) {
      double x = 0;
      ok = ok && number_of(r[c], x) && std::isfinite(x);
    }
    if (ok) out.push_back(r);
  }
  return out;
}

}  // namespace asperity::plot_detail
