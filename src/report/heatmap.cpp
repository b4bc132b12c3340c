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
#include "report/gnuplot.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

bool number_of(const std::string& s, double& x) {
  if (s == "nan" || s == "inf" || s == "-inf") {
    x = s == "nan" ? NAN : (s == "inf" ? INFINITY : -INFINITY);
    return true;
  }
  return scene_io::parse_double(s, x) == scene_io::NumberParse::ok;
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
  if (from_out && png.extension() != ".png")
    throw InputError(png.string(), 0, "--out", "must name a .png file (a plot never writes other files)");
  std::error_code ec;
  const auto st = fs::symlink_status(png, ec);
  if (!fs::exists(st) || png_is_ours(png)) return;
  const fs::path folder = png.parent_path().empty() ? fs::path(".") : png.parent_path();
  if (fs::is_regular_file(st) && fs::equivalent(folder, store, ec)) {
    char head[8] = {};
    std::ifstream(png, std::ios::binary).read(head, sizeof head);
    if (std::string(head, sizeof head) == std::string("\x89PNG\r\n\x1a\n", 8)) return;
  }
  throw InputError(png.string(), 0, from_out ? "--out" : "plot",
                   "refusing to replace a file asperity did not write (only PNGs drawn by asperity are replaced); "
                   "choose a new name");
}

}  // namespace

HeatmapReport plot_heatmap(const fs::path& store, const HeatmapOptions& opt) {
  const fs::path png = opt.out.empty() ? store / ("heatmap_" + file_part(opt.z) + "_over_" + file_part(opt.x) + "_" +
                                                  file_part(opt.y) + ".png")
                                       : opt.out;
  check_png_target(png, store, !opt.out.empty());
  const StoreRows s = read_store(store);
  const std::vector<std::string> cols = csv_split(s.header);
  auto column = [&](const std::string& name, const char* option) -> std::size_t {
    const auto it = std::find(cols.begin(), cols.end(), name);
    if (it == cols.end())
      throw InputError("asperity plot", 0, option,
                       "no column '" + name + "' in the store " + store.string() + "; columns: " + s.header);
    return static_cast<std::size_t>(it - cols.begin());
  };
  const std::size_t cx = column(opt.x, "--x"), cy = column(opt.y, "--y"), cz = column(opt.z, "--z");
  const std::size_t cstatus = column("status", "status"), cgrid = column("grid", "grid");

  std::vector<std::pair<std::size_t, std::string>> filters;
  for (const std::string& w : opt.where) {
    const std::size_t eq = w.find('=');
    if (eq == std::string::npos) throw InputError("asperity plot", 0, "--where", "expected column=value, got '" + w + "'");
    filters.emplace_back(column(w.substr(0, eq), "--where"), w.substr(eq + 1));
  }

  std::vector<std::vector<std::string>> rows;
  for (const auto& [index, text] : s.rows) {
    auto r = csv_split(text);
    if (r.size() != cols.size()) continue;
    bool keep = true;
    for (const auto& [c, v] : filters) keep = keep && same_value(r[c], v);
    double x = 0, y = 0;
    if (keep && number_of(r[cx], x) && number_of(r[cy], y) && std::isfinite(x) && std::isfinite(y))
      rows.push_back(std::move(r));
  }
  if (rows.empty()) throw InputError("asperity plot", 0, "--where", "no point of the store matches (or x/y are not numbers)");

  HeatmapReport rep;
  // Prefer the grids in which both x and y vary (the one-at-a-time grids would pile up at the
  // base values otherwise).
  {
    std::map<std::string, std::pair<std::set<std::string>, std::set<std::string>>> seen;
    for (const auto& r : rows) seen[r[cgrid]].first.insert(r[cx]), seen[r[cgrid]].second.insert(r[cy]);
    std::set<std::string> both;
    for (const auto& [g, xy] : seen)
      if (xy.first.size() > 1 && xy.second.size() > 1) both.insert(g);
    if (!both.empty() && both.size() < seen.size()) {
      std::erase_if(rows, [&](const auto& r) { return !both.count(r[cgrid]); });
      for (const auto& g : both) rep.used_grid += (rep.used_grid.empty() ? "" : ",") + g;
    }
  }

  const std::vector<std::string> xs = distinct_sorted(rows, cx), ys = distinct_sorted(rows, cy);
  auto rank = [](const std::vector<std::string>& v, const std::string& t) {
    for (std::size_t i = 0; i < v.size(); ++i)
      if (same_value(v[i], t)) return i;
    return v.size();
  };
  std::map<std::pair<std::size_t, std::size_t>, const std::vector<std::string>*> cell;
  for (const auto& r : rows) {
    const auto key = std::make_pair(rank(xs, r[cx]), rank(ys, r[cy]));
    const auto [it, fresh] = cell.emplace(key, &r);
    if (fresh) continue;
    std::string differ;  // descriptive columns (before status) where the two points differ
    std::size_t first = 0;
    for (std::size_t c = 2; c < cstatus; ++c)
      if (c != cx && c != cy && !same_value((*it->second)[c], r[c])) {
        differ += (differ.empty() ? "" : ", ") + cols[c];
        if (!first) first = c;
      }
    if (!differ.empty())
      throw InputError("asperity plot", 0, "--where",
                       "several points fall on " + opt.x + " = " + r[cx] + ", " + opt.y + " = " + r[cy] +
                           "; they differ in " + differ + ": pick one, e.g. --where " + cols[first] + "=" + r[first]);
  }

  const bool stand_in = read_file_text(store / "provenance.yaml").find("stand_in_data: true") != std::string::npos;
  std::ostringstream gp;
  // Every text from the store or the command line enters the script as a gnuplot_quote literal;
  // line breaks of the title are gnuplot's "\n" between them.
  std::string title = opt.z + " over " + opt.x + " x " + opt.y;
  for (const std::string& w : opt.where) title += ", " + w;
  gp << "set title " << gnuplot_quote(title);
  if (stand_in) gp << " . \"\\n\" . " << gnuplot_quote("STAND-IN experiments, not measurements");
  gp << " . \"\\n\" . " << gnuplot_quote("(blank: no value: NaN, e.g. no stick-slip cycle, or failed/missing point)") << "\n";
  gp << "set xlabel " << gnuplot_quote(opt.x) << "\nset ylabel " << gnuplot_quote(opt.y) << "\nset cblabel "
     << gnuplot_quote(opt.z) << "\n";
  gp << "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21908d', 3 '#5dc963', 4 '#fde725')\n";
  auto tics = [&](const char* axis, const std::vector<std::string>& v) {
    gp << "set " << axis << "tics (";
    for (std::size_t i = 0; i < v.size(); ++i) gp << (i ? ", " : "") << gnuplot_quote(v[i]) << " " << i;
    gp << ")\n";
  };
  tics("x", xs);
  tics("y", ys);
  if (xs.size() > 12) gp << "set xtics rotate by 60 right\n";
  gp << "set xrange [-0.5:" << xs.size() - 0.5 << "]\nset yrange [-0.5:" << ys.size() - 0.5 << "]\n";
  gp << "$cells << EOD\n";
  for (std::size_t i = 0; i < xs.size(); ++i)
    for (std::size_t j = 0; j < ys.size(); ++j) {
      ++rep.cells;
      double z = NAN;
      if (const auto it = cell.find({i, j}); it != cell.end() && (*it->second)[cstatus] == "ok") number_of((*it->second)[cz], z);
      if (!std::isfinite(z)) {
        ++rep.blank;
        continue;
      }
      gp << i << ' ' << j << ' ' << scene_io::format_double(z) << '\n';
    }
  gp << "EOD\n";
  if (rep.blank < rep.cells)
    gp << "plot $cells using 1:2:(0.5):(0.5):3 with boxxyerror fs solid 1.0 noborder lc palette notitle\n";
  else
    gp << "set label 1 'no finite value' at graph 0.5,0.5 center\nplot NaN notitle\n";

  std::string error;
  if (!render_png(png, gp.str(), 900, 700, &error))
    throw std::runtime_error("cannot draw " + png.string() + ": " + error);
  rep.png = png;
  return rep;
}

}  // namespace asperity
