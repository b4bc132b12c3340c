#include "report/gnuplot.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace asperity {
namespace fs = std::filesystem;

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
  std::string q = "'";
  for (char c : workdir.string()) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  q += "'";
  const std::string cmd = "cd " + q + " && gnuplot " + file.filename().string() + " 2>" +
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

}  // namespace asperity
