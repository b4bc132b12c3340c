#include "report/line_plot.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "report/gnuplot.hpp"
#include "report/plot_axes.hpp"
#include "report/units.hpp"

namespace asperity {
namespace fs = std::filesystem;
using namespace plot_detail;

namespace {

using Row = std::vector<std::string>;
using Lines = std::map<std::string, std::map<double, const Row*>>;

// One line per experiment, points sorted by x; one point per (experiment, x): two that differ
// in a descriptive column → InputError naming a --where filter that picks one.
Lines lines_of(const StoreTable& t, const std::vector<Row>& rows, const LinePlotOptions& opt) {
  const std::size_t cx = t.column(opt.x, "--x"), cstatus = t.column("status", "status"),
                    cexp = t.column("experiment", "experiment");
  Lines lines;
  for (const auto& r : rows) {
    double x = 0;
    number_of(r[cx], x);
    const auto [it, fresh] = lines[r[cexp]].emplace(x, &r);
    if (fresh) continue;
    for (std::size_t c = 2; c < cstatus; ++c)
      if (c != cx && c != cexp && !same_value((*it->second)[c], r[c]))
        throw io::InputError("asperity plot", 0, "--where",
                             "several points of " + r[cexp] + " fall on " + opt.x + " = " + r[cx] +
                                 "; they differ in " + t.cols[c] + ": pick one, e.g. --where " + t.cols[c] + "=" +
                                 r[c]);
  }
  return lines;
}

// Title, mark and axes of the line plot.
std::string line_head(const fs::path& store, const LinePlotOptions& opt, const std::vector<std::string>& xtexts,
                      const std::vector<double>& xv, bool xlog) {
  std::ostringstream gp;
  gp << stand_in_mark(store_is_stand_in(store)) << "set title "
     << gnuplot_quote(column_symbol(opt.y) + " over " + column_symbol(opt.x) + where_title(opt.where));
  gp << "\nset grid\nset key outside right\n";
  gp << axis_settings("x", opt.x, xtexts, {}, xlog);
  gp << "set ylabel " << gnuplot_quote(axis_markup(opt.y)) << "\n";
  if (xlog && xv.size() > 1)
    gp << "set xrange [" << io::format_double(xv.front() / std::pow(xv.back() / xv.front(), 0.03)) << ":"
       << io::format_double(xv.back() * std::pow(xv.back() / xv.front(), 0.03)) << "]\n";
  return gp.str();
}

}  // namespace

LinePlotReport plot_lines(const fs::path& store, const LinePlotOptions& opt) {
  const fs::path figure =
      opt.out.empty() ? store / ("line_" + file_part(opt.y) + "_over_" + file_part(opt.x) + ".png") : opt.out;
  check_png_target(figure, store, !opt.out.empty());
  const StoreTable t(store, opt.where);
  const std::size_t cx = t.column(opt.x, "--x"), cy = t.column(opt.y, "--y");
  const std::size_t cstatus = t.column("status", "status"), cgrid = t.column("grid", "grid");
  t.column("experiment", "experiment");
  std::vector<Row> rows = t.rows_with_numbers({cx});
  if (rows.empty())
    throw io::InputError("asperity plot", 0, "--where", "no point of the store matches (or x is not a number)");

  LinePlotReport rep;
  rep.used_grid = keep_grids_varying(rows, cgrid, {cx});  // the grids in which x varies
  const Lines lines = lines_of(t, rows, opt);
  std::vector<std::string> xtexts = distinct_sorted(rows, cx);
  const double xscale = figure_unit(opt.x).scale, yscale = figure_unit(opt.y).scale;
  std::vector<double> xv(xtexts.size());
  for (std::size_t i = 0; i < xtexts.size(); ++i) number_of(xtexts[i], xv[i]), xv[i] *= xscale;
  const bool xlog = log_axis(xv);

  std::ostringstream gp;
  gp << line_head(store, opt, xtexts, xv, xlog);
  std::size_t k = 0;
  std::string plot = "plot ";
  for (const auto& [experiment, points] : lines) {
    gp << "$line" << k << " << EOD\n";
    for (const auto& [x, r] : points) {
      double y = NAN;
      if ((*r)[cstatus] == "ok") number_of((*r)[cy], y);
      ++rep.points;
      if (!std::isfinite(y)) {
        ++rep.blank;
        gp << "\n";  // a gap in the line
        continue;
      }
      gp << io::format_double(x * xscale) << ' ' << io::format_double(y * yscale) << '\n';
    }
    gp << "EOD\n";
    plot += std::string(k ? ", " : "") + "$line" + std::to_string(k) +
            " using 1:2 with linespoints pt 7 ps 0.8 lw 1.5 title " + gnuplot_text(experiment);
    ++k;
  }
  rep.lines = k;
  gp << (rep.blank < rep.points
             ? plot
             : std::string("set label 1 'no finite value' at graph 0.5,0.5 center\nplot NaN notitle"))
     << "\n";
  std::string error;
  if (!render_plot(figure, gp.str(), 1000, 650, &error))
    throw std::runtime_error("cannot draw " + figure.string() + ": " + error +
                             " (its script is kept: " + plot_script_path(figure).string() + ")");
  rep.figure = figure;
  return rep;
}

}  // namespace asperity
