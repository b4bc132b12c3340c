#include "report/gnuplot.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "scene/csv.hpp"

namespace asperity {
namespace fs = std::filesystem;

std::string shell_quote(const std::string& s) {
  std::string q(1, '\'');
  for (char c : s) {
    if (c == '\'') q.append("'\\''");
    else q.push_back(c);
  }
  q.push_back('\'');
  return q;
}

bool gnuplot_available() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

std::string gnuplot_block(const std::string& name, const std::vector<std::vector<double>>& rows) {
  std::string s = "$" + name + " << EOD\n";
  char buf[32];
  for (const auto& r : rows) {
    bool bad = false;
    for (double x : r) bad = bad || !std::isfinite(x);
    if (!bad) {
      for (std::size_t j = 0; j < r.size(); ++j) {
        std::snprintf(buf, sizeof buf, "%.10g", r[j]);
        if (j) s += ' ';
        s += buf;
      }
    }
    s += '\n';
  }
  return s + "EOD\n";
}

void run_gnuplot(const fs::path& workdir, const std::string& script) {
  if (!gnuplot_available())
    throw std::runtime_error("gnuplot not found: install it (apt-get install gnuplot-nox) to draw plots");
  const fs::path file = workdir / (".plot-" + std::to_string(::getpid()) + ".gp");
  {
    std::ofstream f(file, std::ios::binary | std::ios::trunc);
    f << script;
    if (!f) throw std::runtime_error("cannot write " + file.string());
  }
  const std::string cmd = "cd " + shell_quote(workdir.string()) + " && gnuplot " + file.filename().string() + " 2>" +
                          file.filename().string() + ".err";
  const int rc = std::system(cmd.c_str());
  std::string err;
  {
    std::ifstream e(workdir / (file.filename().string() + ".err"));
    std::getline(e, err);
  }
  std::error_code ec;
  fs::remove(file, ec);
  fs::remove(workdir / (file.filename().string() + ".err"), ec);
  if (rc != 0) throw std::runtime_error("gnuplot failed (status " + std::to_string(rc) + "): " + err);
}

bool render_png(const fs::path& png, const std::string& script, int width, int height) {
  if (!gnuplot_available()) return false;
  // Hidden siblings: ".NAME.png.tmp" and ".NAME.gp".
  fs::path tmp_png = png.parent_path() / ".";
  tmp_png += png.filename();
  tmp_png += ".tmp";
  fs::path gp = png.parent_path() / ".";
  gp += png.stem();
  gp += ".gp";
  std::string text = "set terminal pngcairo size " + std::to_string(width) + "," +
                     std::to_string(height) + " noenhanced\n";
  std::string out_name = tmp_png.string();
  for (char& c : out_name) if (c == '\'') c = '_';  // never inside gnuplot's quotes
  text += "set output '" + out_name + "'\n" + script + "\nunset output\n";
  scene_io::write_text_file(gp, text);
  const int rc = std::system(("gnuplot " + shell_quote(gp.string()) + " >/dev/null 2>&1").c_str());
  std::error_code ec;
  fs::remove(gp, ec);
  if (rc != 0 || !fs::exists(tmp_png)) {
    fs::remove(tmp_png, ec);
    return false;
  }
  fs::rename(tmp_png, png, ec);
  return !ec;
}

}  // namespace asperity
