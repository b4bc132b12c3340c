// Plots a physicist would publish (report/plot_axes.hpp, units.hpp, line_plot.hpp, gnuplot.hpp):
// numeric axes, log scale for logspace grids, units in every label, 1-D line plots, the
// gnuplot script kept beside each figure, a message when gnuplot is missing.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>

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
