#include "bench/gnuplot.hpp"

#include <cstdlib>
#include <system_error>

#include "scene/csv.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {
std::string shell_quote(const std::string& s) {
  std::string q(1, '\'');
  for (char c : s) {
    if (c == '\'') q.append("'\\''");
    else q.push_back(c);
  }
  q.push_back('\'');
  return q;
}
}  // namespace

bool render_png(const fs::path& png, const std::string& script, int width, int height) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) return false;
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
