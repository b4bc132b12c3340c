// Figures for papers (report/gnuplot.hpp, units.hpp; issue 25 item 6): enhanced text whose
// input parts print literally and run nothing, labels that name the quantity with its unit for
// every column a figure can show, --figures png,svg,pdf with each file what its name says.
#include <catch2/catch.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_spawn.hpp"
#include "observe/observables.hpp"
#include "report/gnuplot.hpp"
#include "report/units.hpp"
#include "scene/scene.hpp"
#include "scene/scene_keys.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;
using Catch::Contains;

namespace {

// A name that is enhanced markup in every part and gnuplot code if it ever left its string.
const std::string kHostile = "a_b^c{d}@e&f\\\"; system \"touch x\"";

std::string bytes(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// What gnuplot's enhanced-text parser prints for escaped text: a backslash takes the next
// character literally; any unescaped special character would be markup.
bool literal_read(const std::string& markup, std::string& printed) {
  printed.clear();
  for (std::size_t i = 0; i < markup.size(); ++i) {
    const char c = markup[i];
    if (c == '\\') {
      if (i + 1 == markup.size()) return false;
      printed += markup[++i];
    } else if (std::strchr("^_@&~{}", c)) {
      return false;  // markup
    } else {
      printed += c;
    }
  }
  return true;
}

}  // namespace

TEST_CASE("enhanced_literal escapes every markup character and round-trips", "[report][figures]") {
  CHECK(enhanced_literal(kHostile) == "a\\_b\\^c\\{d\\}\\@e\\&f\\\\\"; system \"touch x\"");
  for (const std::string& s : {kHostile, std::string("plain P4.00N"), std::string("\\"), std::string("x\\"),
                               std::string("α_β^{γ}"), std::string("~~&&@@"), std::string("")}) {
    std::string printed;
    INFO(s);
    CHECK(literal_read(enhanced_literal(s), printed));
    CHECK(printed == s);
  }
  // Inside one gnuplot single-quoted string (no code, no backslash processing there).
  CHECK(gnuplot_text("it's a_b") == "'it' . \"'\" . 's a\\_b'");
}

TEST_CASE("a hostile name prints literally in every format and runs nothing", "[report][figures]") {
  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  const fs::path w = temp_path("figures_hostile");
  fs::remove_all(w);
  fs::create_directories(w);
  const std::string script = "set title " + gnuplot_text(kHostile) + "\nset xlabel " +
                             gnuplot_quote(axis_markup("Q_s")) + "\nplot x title " + gnuplot_text(kHostile) + "\n";
  std::string error;
  REQUIRE(render_figures(w / "hostile.png", script, 600, 400, parse_figure_formats("png,svg,pdf"), &error));
  CHECK(error.empty());
  CHECK_FALSE(fs::exists(w / "x"));  // gnuplot runs in the figure's folder
  const std::string svg = bytes(w / "hostile.svg");
  // Printed as typed (gnuplot writes < > & as XML entities; the quote and backslash as such),
  // one tspan: no sub/superscript, no phantom or overprinted box.
  CHECK_THAT(svg, Contains(">a_b^c{d}@e&amp;f\\\"; system \"touch x\"</tspan>"));
  CHECK(svg.find("&f") == std::string::npos);  // well-formed XML: no raw ampersand
  // The label's markup does format: Q with a lowered s.
  CHECK_THAT(svg, Contains(">Q</tspan>") && Contains("dy=\""));
  fs::remove_all(w);
}

TEST_CASE("every column a figure can show has a label with its quantity and unit", "[report][figures]") {
  std::size_t n = 0;
  for (const SceneKey& k : scene_keys())
    if (k.kind == KeyKind::number || k.kind == KeyKind::integer) {
      INFO(k.name);
      CHECK(has_column_symbol(k.name));
      CHECK(axis_markup(k.name) == column_symbol(k.name) + " [" + unit_markup(figure_unit(k.name).unit) + "]");
      ++n;
    }
  for (const ObservableField& f : observable_fields())
    if (f.kind == ObservableKind::real || f.kind == ObservableKind::count) {
      INFO(f.name);
      CHECK(has_column_symbol(f.name));
      CHECK(axis_markup(f.name) == column_symbol(f.name) + " [" + unit_markup(figure_unit(f.name).unit) + "]");
      ++n;
    }
  for (const std::string& c : all_series()) {
    INFO(c);
    CHECK(has_column_symbol(c));
    CHECK(axis_markup(c) == column_symbol(c) + " [" + unit_markup(figure_unit(c).unit) + "]");
    ++n;
  }
  CHECK(n > 40);
  // Every label's braces pair up (an unpaired one would swallow the rest of the label).
  for (const SceneKey& k : scene_keys()) {
    int depth = 0;
    for (const char c : axis_markup(k.name)) depth += c == '{' ? 1 : c == '}' ? -1 : 0;
    CHECK(depth == 0);
  }
  CHECK(axis_markup("model.alpha_b") == "α_b [m^{2p+2} N^{-2}]");
  CHECK(axis_markup("model.eta") == "η [s^{-1}]");
  CHECK(axis_markup("model.epsilon") == "ε [1]");
  CHECK(axis_markup("experiment.k_L") == "k_L [N/m]");
  CHECK(axis_markup("Q_s") == "Q_s [N]");
  CHECK(axis_markup("A_s") == "A_s [mm^2]");  // areas in mm² (figure_unit)
  CHECK(axis_markup("t_peak") == "t_{peak} [s]");
  CHECK(axis_markup("alpha") == "α [m^2 N^{-2}]");
  CHECK(axis_markup("shape_prefactor") == "shape prefactor c_n [m^2 N^{-n}]");
  CHECK(axis_markup("ss_drop") == "stick-slip drop ΔQ_{ss} [N]");
  CHECK(axis_markup("A") == "A [mm^2]");
  CHECK(axis_markup("A0") == "A_0 [mm^2]");
  // Figure units: SI but the contact areas; the factor from the SI value.
  CHECK(figure_unit("A0").unit == "mm^2");
  CHECK(figure_unit("A0").scale == 1e6);
  CHECK(figure_unit("alpha").unit == "m^2/N^2");  // an area per force², not an area: SI
  CHECK(figure_unit("Q_s").scale == 1);
  CHECK(figure_unit("experiment").unit.empty());
  // A column no table knows (a store's text columns) prints as itself.
  CHECK(axis_markup("experiment") == "experiment");
  CHECK(column_symbol("my_col^2") == "my\\_col\\^2");
}

TEST_CASE("figure formats: png, svg and pdf files of the right kind, sized for a journal column", "[report][figures]") {
  CHECK(parse_figure_formats("png") == FigureFormats{});
  CHECK(parse_figure_formats("pdf, svg") == FigureFormats{false, true, true});
  CHECK(parse_figure_formats("png,svg,pdf,png") == FigureFormats{true, true, true});
  CHECK_THROWS_WITH(parse_figure_formats("jpeg"),
                    Contains("unknown figure format 'jpeg'") && Contains("png, svg or pdf"));
  CHECK_THROWS_WITH(parse_figure_formats(""), Contains("unknown figure format ''"));
  CHECK_THROWS(parse_figure_formats("png,"));
  CHECK(figure_files("d/f.png", {true, true, true}) == std::vector<fs::path>{"d/f.png", "d/f.svg", "d/f.pdf"});
  CHECK(figure_files("d/f.png", {false, false, true}) == std::vector<fs::path>{"d/f.pdf"});

  // PNG as before in pixels; SVG and PDF one column (8.6 cm) or two (17.8 cm), 8.5 pt text.
  CHECK(terminal_for("f.png", 900, 700) == "set terminal pngcairo size 900,700 enhanced");
  CHECK(terminal_for("f.pdf", 1000, 650) == "set terminal pdfcairo size 8.60cm,5.59cm enhanced font 'Sans,8.5'");
  CHECK(terminal_for("f.pdf", 1200, 900) == "set terminal pdfcairo size 17.80cm,13.35cm enhanced font 'Sans,8.5'");
  CHECK(terminal_for("f.svg", 1000, 650) == "set terminal svg size 325,211 enhanced font 'Sans,8.5' fontscale 1.33333");

  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  const fs::path w = temp_path("figures_formats");
  fs::remove_all(w);
  fs::create_directories(w);
  REQUIRE(render_figures(w / "f.png", "set xlabel 'A [mm^2]'\nplot x\n", 500, 300, {true, true, true}));
  const std::string png = bytes(w / "f.png"), svg = bytes(w / "f.svg"), pdf = bytes(w / "f.pdf");
  CHECK(png.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0);
  CHECK(svg.find("<svg") != std::string::npos);
  CHECK(svg.rfind("</svg>") != std::string::npos);
  CHECK(pdf.compare(0, 5, "%PDF-") == 0);
  CHECK(pdf.size() > 1000);
  for (const char* f : {"f.png", "f.svg", "f.pdf"}) CHECK(png_is_ours(w / f));
  const std::string gp = bytes(w / "f.gp");  // one script redraws all three
  CHECK(gp.rfind("# asperity plot script: `gnuplot f.gp` redraws f.png, f.svg, f.pdf (", 0) == 0);
  CHECK_THAT(gp, Contains("set output 'f.png'") && Contains("set output 'f.svg'") && Contains("set output 'f.pdf'"));
  fs::remove_all(w);
}

TEST_CASE("run --plot --figures chooses the formats of the plot, a bad list is a one-line usage error",
          "[cli][figures]") {
  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  const fs::path w = temp_path("figures_cli");
  fs::remove_all(w);
  fs::create_directories(w);
  const fs::path scene = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "campaign" / "tiny_scene.yaml";
  const CliResult r = run_argv(
      w, {"run", scene.string(), "--out", "r", "--set", "stop.time=0.2", "--plot", "--figures", "svg,pdf", "-q"});
  CHECK(r.status == 0);
  CHECK(fs::file_size(w / "r" / "plot.svg") > 0);
  CHECK(bytes(w / "r" / "plot.pdf").compare(0, 5, "%PDF-") == 0);
  CHECK_FALSE(fs::exists(w / "r" / "plot.png"));
  const CliResult bad = run_argv(w, {"run", scene.string(), "--plot", "--figures", "png,gif"});
  CHECK(bad.status == 2);
  CHECK_THAT(bad.err, Contains("--figures") && Contains("unknown figure format 'gif'"));
  fs::remove_all(w);
}
