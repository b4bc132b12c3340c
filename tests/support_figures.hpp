#pragma once
// Reading a figure back: the texts of a gnuplot SVG, each <text> element's tspans joined (as a
// reader sees them, sub- and superscripts inline), and the checks every figure must pass: the
// stand-in mark exactly when its input is a stand-in, each axis labelled with the unit the units
// table gives (report/units.hpp figure_unit).
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "report/gnuplot.hpp"
#include "report/units.hpp"
#include "support_files.hpp"

namespace asperity::testing {

// The texts of an SVG, one per <text> element, tags removed and XML entities decoded.
inline std::vector<std::string> svg_texts(const std::filesystem::path& svg) {
  const std::string s = slurp(svg);
  std::vector<std::string> out;
  for (std::size_t at = s.find("<text"); at != std::string::npos; at = s.find("<text", at + 1)) {
    const std::size_t end = s.find("</text>", at);
    if (end == std::string::npos) break;
    std::string text;
    bool tag = false;
    for (std::size_t i = s.find('>', at) + 1; i < end; ++i) {
      if (s[i] == '<') tag = true;
      if (!tag) text += s[i];
      if (s[i] == '>') tag = false;
    }
    for (const auto& [entity, c] : {std::pair<const char*, const char*>{"&lt;", "<"},
                                    {"&gt;", ">"},
                                    {"&quot;", "\""},
                                    {"&apos;", "'"},
                                    {"&amp;", "&"}})
      for (std::size_t p = text.find(entity); p != std::string::npos; p = text.find(entity, p + 1))
        text.replace(p, std::string(entity).size(), c);
    out.push_back(text);
  }
  return out;
}

// Enhanced-text markup as the figure prints it: ^ _ { } dropped, \x as x.
inline std::string printed(const std::string& markup) {
  std::string out;
  for (std::size_t i = 0; i < markup.size(); ++i) {
    const char c = markup[i];
    if (c == '\\' && i + 1 < markup.size())
      out += markup[++i];
    else if (c != '^' && c != '_' && c != '{' && c != '}')
      out += c;
  }
  return out;
}

inline bool has_text(const std::vector<std::string>& texts, const std::string& text) {
  for (const std::string& t : texts)
    if (t == text) return true;
  return false;
}

// The checks of one figure: the mark exactly when `stand_in`; for each column, an axis label
// that is its symbol and the unit figure_unit gives (areas in mm²).
inline void check_figure(const std::filesystem::path& svg, bool stand_in, const std::vector<std::string>& columns) {
  INFO(svg.string() << (stand_in ? " (stand-in input)" : " (measured input)"));
  REQUIRE(std::filesystem::exists(svg));
  const std::vector<std::string> texts = svg_texts(svg);
  std::string all;
  for (const std::string& t : texts) all += "\n  " + t;
  INFO("its texts:" << all);
  CHECK(has_text(texts, kStandInMark) == stand_in);
  for (const std::string& column : columns) {
    const std::string unit = figure_unit(column).unit;
    INFO(column << ": unit " << unit);
    REQUIRE_FALSE(unit.empty());
    CHECK(has_text(texts, printed(column_symbol(column) + " [" + unit_markup(unit) + "]")));
  }
}

// The end of a figure test's folder `w`: copied first into $ASPERITY_KEEP_FIGURES/NAME when that
// is set (scripts/check_svgs.sh renders the kept SVGs in a browser), then removed.
inline void done_with(const std::filesystem::path& w) {
  namespace fs = std::filesystem;
  if (const char* keep = std::getenv("ASPERITY_KEEP_FIGURES"); keep && *keep) {
    fs::create_directories(fs::path(keep) / w.filename());
    fs::copy(w, fs::path(keep) / w.filename(), fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  }
  fs::remove_all(w);
}

}  // namespace asperity::testing
