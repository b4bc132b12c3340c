#include "report/heatmap.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "campaign/store.hpp"
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
using Cells = std::map<std::pair<std::size_t, std::size_t>, const Row*>;

// The point of each (x rank, y rank) cell; two points on one cell that differ in a descriptive
// column (before status) → InputError naming a --where filter that picks one.
Cells cells_of(const StoreTable& t, const std::vector<Row>& rows, const HeatmapOptions& opt,
               const std::vector<std::string>& xs, const std::vector<std::string>& ys) {
  const std::size_t cx = t.column(opt.x, "--x"), cy = t.column(opt.y, "--y");
  const std::size_t cstatus = t.column("status", "status");
  auto rank = [](const std::vector<std::string>& v, const std::string& text) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (same_value(v[i], text)) return i;
    return v.size();
  };
  Cells cell;
  for (const auto& r : rows) {
    const auto key = std::make_pair(rank(xs, r[cx]), rank(ys, r[cy]));
    const auto [it, fresh] = cell.emplace(key, &r);
    if (fresh) continue;
    std::string differ;  // descriptive columns (before status) where the two points differ
    std::size_t first = 0;
    for (std::size_t c = 2; c < cstatus; ++c)
      if (c != cx && c != cy && !same_value((*it->second)[c], r[c])) {
        differ += (differ.empty() ? "" : ", ") + t.cols[c];
        if (!first) first = c;
      }
    if (!differ.empty())
      throw io::InputError("asperity plot", 0, "--where",
                           "several points fall on " + opt.x + " = " + r[cx] + ", " + opt.y + " = " + r[cy] +
                               "; they differ in " + differ + ": pick one, e.g. --where " + t.cols[first] + "=" +
                               r[first]);
  }
  return cell;
}

// The store texts' values in the column's figure unit.
std::vector<double> figure_values(const std::vector<std::string>& texts, const std::string& column) {
  const double scale = figure_unit(column).scale;
  std::vector<double> v(texts.size());
  for (std::size_t i = 0; i < texts.size(); ++i) number_of(texts[i], v[i]), v[i] *= scale;
  return v;
}

// Title, mark, colour bar and palette of the heat map.
std::string heatmap_head(const fs::path& store, const HeatmapOptions& opt) {
  std::ostringstream gp;
  // Every text from the store or the command line enters the script as a gnuplot_quote literal
  // (and its markup through enhanced_literal); line breaks of the title are gnuplot's "\n" between them.
  const std::string title =
      column_symbol(opt.z) + " over " + column_symbol(opt.x) + " × " + column_symbol(opt.y) + where_title(opt.where);
  gp << stand_in_mark(store_is_stand_in(store)) << "set title " << gnuplot_quote(title);
  gp << " . \"\\n\" . " << gnuplot_quote("(blank: no value (NaN), or a failed point)") << "\n";
  // Room for the colour box, its tics and its label: at one journal column's width gnuplot
  // left the label out of the SVG and PDF.
  gp << "set rmargin at screen 0.74\n";
  // In SVG the colour bar's label sits at a fixed place by the figure's right edge: gnuplot's svg
  // terminal places cblabel by an estimate of the tic labels' width that falls a character or
  // two short at a journal column's size, so six-character tics ran into it (cairo measures).
  const std::string label = gnuplot_quote(axis_markup(opt.z));
  gp << "if (GPVAL_TERM eq 'svg') { set label 98 " << label
     << " at screen 0.975, graph 0.5 center rotate by 90 } else { set cblabel " << label << " }\n";
  gp << "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21908d', 3 '#5dc963', 4 '#fde725')\n";
  return gp.str();
}

}  // namespace

HeatmapReport plot_heatmap(const fs::path& store, const HeatmapOptions& opt) {
  const fs::path png =
      opt.out.empty()
          ? store / ("heatmap_" + file_part(opt.z) + "_over_" + file_part(opt.x) + "_" + file_part(opt.y) + ".png")
          : opt.out;
  check_png_target(png, store, !opt.out.empty());
  const StoreTable t(store, opt.where);
  const std::size_t cx = t.column(opt.x, "--x"), cy = t.column(opt.y, "--y"), cz = t.column(opt.z, "--z");
  const std::size_t cstatus = t.column("status", "status"), cgrid = t.column("grid", "grid");
  std::vector<Row> rows = t.rows_with_numbers({cx, cy});
  if (rows.empty())
    throw io::InputError("asperity plot", 0, "--where", "no point of the store matches (or x/y are not numbers)");

  HeatmapReport rep;
  // Prefer the grids in which both x and y vary.
  rep.used_grid = keep_grids_varying(rows, cgrid, {cx, cy});
  const std::vector<std::string> xs = distinct_sorted(rows, cx), ys = distinct_sorted(rows, cy);
  const Cells cell = cells_of(t, rows, opt, xs, ys);

  std::ostringstream gp;
  gp << heatmap_head(store, opt);
  // Numeric axes: each cell spans the values between its neighbours, so η = 150, 180, 200 sit
  // where they are, and a logspace axis (α_b, c_min) is drawn on a log scale.
  const std::vector<double> xv = figure_values(xs, opt.x), yv = figure_values(ys, opt.y);
  const double zscale = figure_unit(opt.z).scale;
  const bool xlog = log_axis(xv), ylog = log_axis(yv);
  const auto xe = cell_edges(xv, xlog), ye = cell_edges(yv, ylog);
  gp << "$cells << EOD\n";
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (std::size_t j = 0; j < ys.size(); ++j) {
      ++rep.cells;
      double z = NAN;
      if (const auto it = cell.find({i, j}); it != cell.end() && (*it->second)[cstatus] == "ok")
        number_of((*it->second)[cz], z);
      if (!std::isfinite(z)) {
        ++rep.blank;
        continue;
      }
      using io::format_double;
      gp << format_double(xv[i]) << ' ' << format_double(yv[j]) << ' ' << format_double(xe[i].first) << ' '
         << format_double(xe[i].second) << ' ' << format_double(ye[j].first) << ' ' << format_double(ye[j].second)
         << ' ' << format_double(z * zscale) << '\n';
    }
  gp << "EOD\n";
  const bool any_value = rep.blank < rep.cells;
  // The colour bar's tics from the values (stats before the x and y ranges, which would filter
  // them out); one tic at the value when all are equal, where a step has nothing to divide.
  if (any_value) gp << tics_for_span("cb", "$cells", "7") << "if (STATS_max == STATS_min) { set cbtics (STATS_min) }\n";
  gp << axis_settings("x", opt.x, xs, xe, xlog) << axis_settings("y", opt.y, ys, ye, ylog);
  if (any_value)
    gp << "plot $cells using 1:2:3:4:5:6:7 with boxxyerror fs solid 1.0 noborder lc palette notitle\n";
  else
    gp << "set label 1 'no finite value' at graph 0.5,0.5 center\nplot NaN notitle\n";

  std::string error;
  if (!render_plot(png, gp.str(), 900, 700, &error))
    throw std::runtime_error("cannot draw " + png.string() + ": " + error);
  rep.png = png;
  return rep;
}

}  // namespace asperity
