// Plots a physicist would publish (report/plot_axes.hpp, units.hpp, line_plot.hpp, gnuplot.hpp):
// numeric axes, log scale for logspace grids, units in every label, 1-D line plots, the
// gnuplot script kept beside each figure, a message when gnuplot is missing.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>

#include "campaign/campaign_load.hpp"
#include "campaign/sweep.hpp"
#include "report/gnuplot.hpp"
#include "report/heatmap.hpp"
#include "report/line_plot.hpp"
#include "report/plot_axes.hpp"
#include "report/units.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;
using Catch::Contains;
using Catch::Matchers::WithinRel;

TEST_CASE("axes: log scale for logspace or wide values, cells between the values", "[report][plots]") {
  using namespace plot_detail;
  CHECK(log_axis({1e-4, 1e-3, 1e-2}));       // logspace
  CHECK(log_axis({3e-16, 6e-16, 1.2e-15}));  // logspace, less than two decades
  CHECK_FALSE(log_axis({150, 180, 200}));    // irregular, narrow
  CHECK_FALSE(log_axis({0.5, 0.6, 0.7}));    // linspace
  CHECK(log_axis({1e-5, 1e-2}));             // two values, three decades
  CHECK_FALSE(log_axis({0, 50, 100}));       // not positive
  const auto lin = cell_edges({150, 180, 200}, false);
  CHECK(lin[0] == std::pair<double, double>{135, 165});
  CHECK(lin[1] == std::pair<double, double>{165, 190});
  CHECK(lin[2] == std::pair<double, double>{190, 210});
  const auto log = cell_edges({1, 10, 100}, true);
  CHECK_THAT(log[0].first, WithinRel(std::pow(10.0, -0.5), 1e-14));
  CHECK_THAT(log[1].first, WithinRel(std::pow(10.0, 0.5), 1e-14));
  CHECK_THAT(log[2].second, WithinRel(std::pow(10.0, 2.5), 1e-14));
}

TEST_CASE("tic labels and titles fit one journal column", "[report][plots]") {
  using namespace plot_detail;
  // η of the shipped campaign, cells over [-25, 275] on an x axis of 28 characters: 150 and 180
  // sit 2.8 characters apart, less than half of two 3-character labels plus one; 200 sits 4.7
  // from 150. Every value keeps its tic.
  const std::vector<std::string> eta{"0", "50", "100", "150", "180", "200", "250"};
  const std::string x =
      axis_settings("x", "model.eta", eta, cell_edges({0, 50, 100, 150, 180, 200, 250}, false), false);
  CHECK_THAT(x, Contains("'100' 100, '150' 150, '' 180, '200' 200, '250' 250)"));
  // ε over [0.45, 1.01] on a y axis of 10 lines: 0.95 sits 0.9 lines above 0.9 (1.5 needed).
  const std::vector<double> eps{0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99};
  const std::string y = axis_settings("y", "model.epsilon", {"0.5", "0.6", "0.7", "0.8", "0.9", "0.95", "0.99"},
                                      cell_edges(eps, false), false);
  CHECK_THAT(y, Contains("'0.9' 0.9, '' 0.95, '0.99' 0.99)"));
  // Titles: broken at spaces into lines of at most 50 characters, every word kept in order, a
  // word longer than a line cut.
  const std::string words = "calibration of the six loads / P0.98N: objective (chi-square of A(Q) and Q(t))";
  const std::string long_word(60, 'w');
  for (const std::string& text : {words, long_word, std::string("short")}) {
    const std::string expr = title_lines(text);
    std::string joined, line;
    std::size_t lines = 0;
    for (std::size_t from = 0;;) {
      const std::string between = " . \"\\n\" . ";
      const std::size_t cut = expr.find(between, from);
      line = expr.substr(from, cut == std::string::npos ? std::string::npos : cut - from);
      REQUIRE(line.size() >= 2);
      line = line.substr(1, line.size() - 2);  // the quotes of gnuplot_text (no markup in these texts)
      CHECK(line.size() <= kColumnTitleChars);
      joined += (joined.empty() || text == long_word ? "" : " ") + line;
      ++lines;
      if (cut == std::string::npos) break;
      from = cut + between.size();
    }
    CHECK(joined == text);
    CHECK(lines == (text.size() + kColumnTitleChars - 1) / kColumnTitleChars);
  }
}

TEST_CASE("units of columns come from the key and observable tables", "[report][plots]") {
  CHECK(axis_label("model.eta") == "model.eta [1/s]");
  CHECK(axis_label("model.epsilon") == "model.epsilon [1]");
  CHECK(axis_label("Q_s") == "Q_s [N]");
  CHECK(axis_label("A_s") == "A_s [m^2]");
  CHECK(axis_label("experiment.mass") == "experiment.mass [kg]");
  CHECK(axis_label("experiment") == "experiment");
  CHECK(column_unit("ss_cycles") == "1");
}

TEST_CASE("heat map and line plot of a logspace grid: log axis, units, one line per experiment, script kept",
          "[report][plots]") {
  const fs::path w = temp_path("plots");
  fs::remove_all(w);
  fs::create_directories(w);
  const fs::path data = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "campaign";
  const fs::path campaign = write_text(w / "c.yaml", "name: logs\nscenes: [" + (data / "tiny_scene.yaml").string() +
                                                         "]\nset: {stop.time: 0.3}\naxes:\n  model.c_min: {logspace: "
                                                         "[1.0e-4, 1.0e-2, 3]}\n  model.eta: [0, 100, 250]\n");
  SweepOptions o;
  o.out = w / "store";
  o.threads = 1;
  o.quiet = true;
  run_sweep(load_campaign(campaign), o);

  HeatmapOptions h;
  h.x = "model.c_min";
  h.y = "model.eta";
  h.z = "Q_s";
  const bool drawn = io::gnuplot_available();
  const fs::path gp = w / "store" / "heatmap_Q_s_over_model_c_min_model_eta.gp";
  if (drawn) {
    const HeatmapReport r = plot_heatmap(w / "store", h);
    CHECK(r.cells == 9);
    CHECK(png_is_ours(r.png));
  } else {
    CHECK_THROWS_WITH(plot_heatmap(w / "store", h), Contains("gnuplot not found"));
  }
  const std::string script = slurp(gp);
  CHECK_THAT(script, Contains("set logscale x") && Contains("set xlabel 'c_{min} [1]'") &&
                         Contains("set ylabel 'η [s^{-1}]'") && Contains("set cblabel 'Q_s [N]'"));
  CHECK(script.find("set logscale y") == std::string::npos);  // 0, 100, 250: linear
  CHECK(script.rfind("# asperity plot script", 0) == 0);
  if (drawn) {
    // At one journal column (SVG) the colour bar's label clears its tic labels: each tic label's
    // right end from DejaVu Sans's advances (digits 0.636 em, 'e' 0.615, '-' 0.361, '.' and ' '
    // 0.318), the rotated label's left edge at its ascent (0.76 em). gnuplot's own cblabel sat
    // 4.5 px into its nine tics. At most six tics.
    h.out = w / "heat.svg";
    plot_heatmap(w / "store", h);
    const std::string svg = slurp(h.out);
    const std::regex tic(
        R"re(translate\(([0-9.]+),[0-9.]+\)" stroke="none" fill="black" font-family="Sans" )re"
        R"re(font-size="([0-9.]+)"  text-anchor="start">\s*<text><tspan font-family="Sans" >( ?[-0-9.e]+)<)re");
    const std::regex label(R"re(translate\(([0-9.]+),[0-9.]+\) rotate\((?:-90|270)\)" stroke="none" fill="black" )re"
                           R"re(font-family="Sans" font-size="([0-9.]+)"  text-anchor="middle">\s*<text><tspan )re"
                           R"re(font-family="Sans" >Q<)re");
    double tics_right = 0;
    int cb_tics = 0;
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), tic); it != std::sregex_iterator(); ++it) {
      const double x = std::stod((*it)[1]), em = std::stod((*it)[2]);
      ++cb_tics;
      double advance = 0;
      for (const char c : (*it)[3].str())
        advance += c == 'e' ? 0.615 : c == '-' ? 0.361 : (c == '.' || c == ' ') ? 0.318 : 0.636;
      tics_right = std::max(tics_right, x + advance * em);
    }
    std::smatch m;
    REQUIRE(std::regex_search(svg, m, label));
    const double label_left = std::stod(m[1]) - 0.76 * std::stod(m[2]);
    CHECK(cb_tics >= 2);
    CHECK(cb_tics <= 6);
    CHECK(label_left > tics_right);
  }

  LinePlotOptions l;
  l.x = "model.c_min";
  l.y = "Q_s";
  l.where = {"model.eta=100"};
  l.out = w / "line.svg";
  if (drawn) {
    const LinePlotReport r = plot_lines(w / "store", l);
    CHECK(r.lines == 1);  // one experiment in the fixture
    CHECK(r.points == 3);
    CHECK(png_is_ours(w / "line.svg"));
  } else {
    CHECK_THROWS(plot_lines(w / "store", l));
  }
  const std::string line = slurp(w / "line.gp");
  CHECK_THAT(line, Contains("set terminal svg") && Contains("$line0 << EOD") && Contains("set logscale x") &&
                       Contains("set ylabel 'Q_s [N]'") && Contains("title 'small'"));
  CHECK(line.find("$line1") == std::string::npos);
  fs::remove_all(w);
}

TEST_CASE("a missing gnuplot is said, the script is still kept, a foreign script is not replaced", "[report][plots]") {
  const fs::path w = temp_path("plots_nognuplot");
  fs::remove_all(w);
  fs::create_directories(w);
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", "/nonexistent", 1);
  std::string error;
  const bool ok = render_plot(w / "f.png", "plot x\n", 400, 300, &error);
  ::setenv("PATH", path.c_str(), 1);
  CHECK_FALSE(ok);
  CHECK(error == "gnuplot not found on the PATH");
  CHECK_FALSE(fs::exists(w / "f.png"));
  CHECK_THAT(slurp(w / "f.gp"), Contains("set output 'f.png'") && Contains("plot x"));
  write_text(w / "g.gp", "my own script\n");
  CHECK_FALSE(keep_plot_script(w / "g.gp", "# asperity plot script\n"));
  CHECK(slurp(w / "g.gp") == "my own script\n");
  fs::remove_all(w);
}
