#include "report/heatmap.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "campaign/store.hpp"
#include "scene/input_error.hpp"
#include "scene/numbers.hpp"

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

}  // namespace

HeatmapReport plot_heatmap(const fs::path& store, const HeatmapOptions& opt) {
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
  gp << "set terminal pngcairo size 900,700 noenhanced\n";
  const fs::path png = opt.out.empty() ? store / ("heatmap_" + file_part(opt.z) + "_over_" + file_part(opt.x) + "_" +
                                                  file_part(opt.y) + ".png")
                                       : opt.out;
  const fs::path tmp = png.parent_path() / std::string(".").append(png.filename().string()).append(".tmp");
  gp << "set output '" << tmp.string() << "'\n";
  std::string title = opt.z + " over " + opt.x + " x " + opt.y;
  for (const std::string& w : opt.where) title += ", " + w;
  if (stand_in) title += "\\nSTAND-IN experiments, not measurements";
  title += "\\n(blank: no value: NaN, e.g. no stick-slip cycle, or failed/missing point)";
  gp << "set title \"" << title << "\"\n";
  gp << "set xlabel '" << opt.x << "'\nset ylabel '" << opt.y << "'\nset cblabel '" << opt.z << "'\n";
  gp << "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21908d', 3 '#5dc963', 4 '#fde725')\n";
  auto tics = [&](const char* axis, const std::vector<std::string>& v) {
    gp << "set " << axis << "tics (";
    for (std::size_t i = 0; i < v.size(); ++i) gp << (i ? ", " : "") << "\"" << v[i] << "\" " << i;
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

  FILE* pipe = ::popen("gnuplot", "w");
  if (!pipe) throw std::runtime_error("cannot start gnuplot");
  const std::string script = gp.str();
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int rc = ::pclose(pipe);
  std::error_code ec;
  if (rc != 0 || !fs::exists(tmp)) {
    fs::remove(tmp, ec);
    throw std::runtime_error("gnuplot failed (is gnuplot installed?) while drawing " + png.string());
  }
  fs::rename(tmp, png);
  rep.png = png;
  return rep;
}

}  // namespace asperity
