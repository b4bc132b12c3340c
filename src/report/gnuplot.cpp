#include "report/gnuplot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "io/atomic_file.hpp"
#include "io/numbers.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

std::uint32_t crc32(const unsigned char* p, std::size_t n, std::uint32_t crc = 0xffffffffu) {
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return crc;
}

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
const std::string kOurText = std::string("Software") + '\0' + "asperity";

std::uint32_t be32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}

std::string read_all(const fs::path& p, std::size_t max_bytes) {
  std::ifstream f(p, std::ios::binary);
  std::string s(max_bytes, '\0');
  f.read(s.data(), static_cast<std::streamsize>(max_bytes));
  s.resize(static_cast<std::size_t>(f.gcount()));
  return s;
}

// Inserts the tEXt chunk "Software" = "asperity" after IHDR (the first chunk, 25 bytes).
bool tag_png(const fs::path& png) {
  std::ifstream in(png, std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (s.size() < 33 || std::memcmp(s.data(), kPngSignature, 8) != 0 || s.compare(12, 4, "IHDR") != 0) return false;
  std::string chunk;
  auto put32 = [&](std::uint32_t v) {
    for (int i = 3; i >= 0; --i) chunk.push_back(static_cast<char>((v >> (8 * i)) & 0xffu));
  };
  put32(static_cast<std::uint32_t>(kOurText.size()));
  const std::string body = "tEXt" + kOurText;
  chunk += body;
  put32(crc32(reinterpret_cast<const unsigned char*>(body.data()), body.size()) ^ 0xffffffffu);
  s.insert(33, chunk);
  try {
    io::write_file_atomically(png, s, io::Durability::unsynced);
  } catch (const std::runtime_error&) {
    return false;
  }
  return true;
}

}  // namespace

std::string gnuplot_quote(const std::string& text) {
  // Single-quoted pieces joined with "'" by gnuplot's `.` operator. Doubling the quote is not
  // enough: gnuplot 5.4 misreads two doubled quotes in a row (a syntax error at best).
  std::string out, piece;
  bool empty = true;
  const auto emit = [&](const std::string& literal) {
    if (!empty) out += " . ";
    out += literal;
    empty = false;
  };
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\'') {
      if (!piece.empty()) emit("'" + piece + "'");
      piece.clear();
      emit("\"'\"");
    } else {
      piece += (u < 0x20 || u == 0x7f) ? '?' : c;
    }
  }
  if (!piece.empty() || empty) emit("'" + piece + "'");
  return out;
}

std::string enhanced_literal(const std::string& text) {
  std::string out;
  out.reserve(text.size() + 8);
  for (const char c : text) {
    switch (c) {
      case '^':
      case '_':
      case '@':
      case '&':
      case '~':
      case '{':
      case '}':
      case '\\':
        out += '\\';
        break;
      default:
        break;
    }
    out += c;
  }
  return out;
}

std::string gnuplot_text(const std::string& text) { return gnuplot_quote(enhanced_literal(text)); }

std::string stand_in_mark(bool stand_in) {
  if (!stand_in) return "";
  return "set label 99 " + gnuplot_text(kStandInMark) +
         " at screen 0.995, 0.012 right front textcolor rgb '#b2182b' font ',8'\n";
}

std::string tics_for_span(const char* axis, const std::string& source, const std::string& column, bool from_zero) {
  const std::string span = from_zero ? "STATS_max" : "(STATS_max - STATS_min)";
  // The smallest step of 1, 2 or 5 times a power of ten leaving at most five intervals.
  return "stats " + source + " using " + column + " nooutput\nstep = " + span + " > 0 ? 10**floor(log10(" + span +
         " / 5.0)) : 1\nm = " + span + " > 0 ? " + span + " / (5.0 * step) : 1\n" +
         "tic = (m <= 1 ? 1 : (m <= 2 ? 2 : (m <= 5 ? 5 : 10))) * step\nset " + axis + "tics tic\n";
}

std::string title_lines(const std::string& text, std::size_t width) {
  // Greedy word wrap; a word longer than a line is cut. Lengths count UTF-8 characters.
  const auto chars = [](const std::string& s) {
    return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
  };
  std::vector<std::string> lines;
  std::string line;
  const auto flush = [&] {
    if (!line.empty()) lines.push_back(line), line.clear();
  };
  std::istringstream words(text);
  for (std::string w; words >> w;) {
    while (chars(w) > width) {
      std::size_t cut = 0;
      for (std::size_t n = 0; n < width; ++n) {
        ++cut;  // past one character: its lead byte, then its continuation bytes
        while (cut < w.size() && (w[cut] & 0xC0) == 0x80) ++cut;
      }
      flush();
      lines.push_back(w.substr(0, cut));
      w.erase(0, cut);
    }
    if (!line.empty() && chars(line) + 1 + chars(w) > width) flush();
    line += (line.empty() ? "" : " ") + w;
  }
  flush();
  if (lines.empty()) lines.emplace_back();
  std::string expr;
  for (std::size_t i = 0; i < lines.size(); ++i) expr += (i ? " . \"\\n\" . " : "") + gnuplot_text(lines[i]);
  return expr;
}

FigureFormats parse_figure_formats(const std::string& list) {
  FigureFormats f{false, false, false};
  std::size_t begin = 0;
  bool any = false;
  while (begin <= list.size()) {
    const std::size_t comma = std::min(list.find(',', begin), list.size());
    std::string name = list.substr(begin, comma - begin);
    while (!name.empty() && name.front() == ' ') name.erase(name.begin());
    while (!name.empty() && name.back() == ' ') name.pop_back();
    if (name == "png")
      f.png = true;
    else if (name == "svg")
      f.svg = true;
    else if (name == "pdf")
      f.pdf = true;
    else
      throw std::invalid_argument("unknown figure format '" + name + "' (use png, svg or pdf, comma-separated)");
    any = true;
    begin = comma + 1;
  }
  if (!any) throw std::invalid_argument("no figure format (use png, svg or pdf, comma-separated)");
  return f;
}

std::vector<fs::path> figure_files(const fs::path& figure, const FigureFormats& formats) {
  std::vector<fs::path> out;
  for (const auto& [on, ext] : {std::pair{formats.png, ".png"}, {formats.svg, ".svg"}, {formats.pdf, ".pdf"}})
    if (on) out.push_back(fs::path(figure).replace_extension(ext));
  return out;
}

std::string gnuplot_block(const std::string& name, const std::vector<std::vector<double>>& rows) {
  std::string s = "$" + name + " << EOD\n";
  for (const auto& r : rows) {
    bool bad = false;
    for (double x : r) bad = bad || !std::isfinite(x);
    if (!bad) {
      for (std::size_t j = 0; j < r.size(); ++j) {
        if (j) s += ' ';
        s += io::format_significant(r[j], 10);
      }
    }
    s += '\n';
  }
  return s + "EOD\n";
}

namespace {
const std::string kScriptHeader = "# asperity plot script";

// Journal sizes: a column of a two-column page (8.6 cm, e.g. Physical Review) and the full
// width (17.8 cm); text in 8.5 pt.
constexpr double kColumnCm = 8.6, kPageCm = 17.8, kPaperFontPt = 8.5;

// gnuplot 5.4's svg terminal writes an escaped \& as a raw & (not XML); the octal escape \046
// comes out as &amp;. Only enhanced_literal writes \& (a raw & of markup is never written).
std::string svg_ampersands(const std::string& script) {
  std::string out;
  out.reserve(script.size());
  for (std::size_t i = 0; i < script.size(); ++i) {
    if (script[i] == '\\' && i + 1 < script.size()) {
      if (script[i + 1] == '&') {
        out += "\\046";
      } else {
        out += script[i];
        out += script[i + 1];
      }
      ++i;
      continue;
    }
    out += script[i];
  }
  return out;
}

}  // namespace

std::string script_for_terminal(const fs::path& figure, const std::string& script) {
  return figure.extension() == ".svg" ? svg_ampersands(script) : script;
}

std::string terminal_for(const fs::path& figure, int width, int height) {
  const std::string ext = figure.extension().string();
  const double w_cm = width <= 1000 ? kColumnCm : kPageCm, h_cm = w_cm * height / std::max(width, 1);
  char buf[160];
  if (ext == ".svg") {  // CSS pixels, 96 per inch; fonts scaled from points to them
    std::snprintf(buf, sizeof buf, "set terminal svg size %d,%d enhanced font 'Sans,%g' fontscale %.6g",
                  static_cast<int>(std::lround(w_cm / 2.54 * 96)), static_cast<int>(std::lround(h_cm / 2.54 * 96)),
                  kPaperFontPt, 96.0 / 72.0);
    return buf;
  }
  if (ext == ".pdf") {
    std::snprintf(buf, sizeof buf, "set terminal pdfcairo size %.2fcm,%.2fcm enhanced font 'Sans,%g'", w_cm, h_cm,
                  kPaperFontPt);
    return buf;
  }
  return "set terminal pngcairo size " + std::to_string(width) + "," + std::to_string(height) + " enhanced";
}

fs::path plot_script_path(const fs::path& figure) {
  fs::path gp = figure;
  return gp.replace_extension(".gp");
}

bool keep_plot_script(const fs::path& gp, const std::string& script) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(gp, ec)) && read_all(gp, kScriptHeader.size()) != kScriptHeader) return false;
  try {
    io::write_file_atomically(gp, script, io::Durability::unsynced);
  } catch (const std::runtime_error&) {
    return false;
  }
  return true;
}

namespace {

// The kept script: its header names every figure it redraws, then per figure the terminal,
// the output and the whole script.
std::string kept_script(const std::vector<fs::path>& figures, const std::string& script, int width, int height) {
  std::string names;
  for (const fs::path& f : figures) names += (names.empty() ? "" : ", ") + f.filename().string();
  std::string text = kScriptHeader + ": `gnuplot " + plot_script_path(figures.front()).filename().string() +
                     "` redraws " + names + " (data inline; restyle freely)\n";
  for (std::size_t i = 0; i < figures.size(); ++i) {
    if (i) text += '\n';
    text += terminal_for(figures[i], width, height);
    text += "\nset output " + gnuplot_quote(figures[i].filename().string()) + "\n";
    text += script_for_terminal(figures[i], script);
    text += "\nunset output\n";
  }
  return text;
}

// Draws one figure (the script kept by the caller).
bool draw(const fs::path& figure, const std::string& script, int width, int height, std::string* error) {
  if (!io::gnuplot_available()) {
    if (error) *error = "gnuplot not found on the PATH";
    return false;
  }
  // gnuplot writes to a name of our own making (no user text in `set output`), in the target's
  // folder so that the rename is atomic.
  const fs::path dir = figure.parent_path().empty() ? fs::path(".") : figure.parent_path();
  const std::string tmp_name = ".plot.tmp-" + io::unique_tmp_suffix();  // the ".NAME.tmp-*" pattern of output_dir
  const fs::path tmp = dir / tmp_name;
  const io::TempGuard on_signal(tmp);
  const std::string text = terminal_for(figure, width, height) + "\nset output " + gnuplot_quote(tmp_name) + "\n" +
                           script_for_terminal(figure, script) + "\nunset output\n";
  std::error_code ec;
  try {
    io::run_gnuplot(dir, text);
  } catch (const std::exception& e) {
    if (error) *error = e.what();
    fs::remove(tmp, ec);
    return false;
  }
  const bool png = figure.extension() == ".png";
  if (!fs::exists(tmp) || (png && !tag_png(tmp))) {
    if (error) *error = "gnuplot wrote no figure";
    fs::remove(tmp, ec);
    return false;
  }
  fs::rename(tmp, figure, ec);
  if (ec) {
    if (error) *error = "cannot move the plot to " + figure.string() + ": " + ec.message();
    fs::remove(tmp, ec);
    return false;
  }
  return true;
}

}  // namespace

bool render_plot(const fs::path& figure, const std::string& script, int width, int height, std::string* error) {
  // The kept script draws the figure by its own name, from its own folder.
  keep_plot_script(plot_script_path(figure), kept_script({figure}, script, width, height));
  return draw(figure, script, width, height, error);
}

bool render_figures(const fs::path& figure, const std::string& script, int width, int height,
                    const FigureFormats& formats, std::string* error) {
  const std::vector<fs::path> figures = figure_files(figure, formats);
  if (figures.empty()) return true;
  keep_plot_script(plot_script_path(figure), kept_script(figures, script, width, height));
  bool ok = true;
  for (const fs::path& f : figures) {
    std::string why;
    if (!draw(f, script, width, height, &why) && ok) {
      ok = false;
      if (error) *error = why;
    }
  }
  return ok;
}

bool png_is_ours(const fs::path& png) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(png, ec))) return false;
  if (png.extension() != ".png") {  // SVG, PDF: our kept script names it
    std::string head = read_all(plot_script_path(png), 1024);
    head = head.substr(0, head.find('\n'));
    const std::size_t from = head.find("` redraws "), to = head.rfind(" (data inline");
    if (head.rfind(kScriptHeader, 0) != 0 || from == std::string::npos || to == std::string::npos || to < from)
      return false;
    const std::string names = ", " + head.substr(from + 10, to - from - 10) + ", ";
    return names.find(", " + png.filename().string() + ", ") != std::string::npos;
  }
  const std::string s = read_all(png, 1 << 16);
  if (s.size() < 8 || std::memcmp(s.data(), kPngSignature, 8) != 0) return false;
  for (std::size_t at = 8; at + 12 <= s.size();) {  // chunks: length, type, data, CRC
    const std::uint32_t len = be32(s, at);
    const std::string type = s.substr(at + 4, 4);
    if (type == "IDAT" || type == "IEND" || at + 12 + len > s.size()) return false;
    if (type == "tEXt" && s.compare(at + 8, len, kOurText) == 0 && len == kOurText.size()) return true;
    at += 12 + static_cast<std::size_t>(len);
  }
  return false;
}

}  // namespace asperity
