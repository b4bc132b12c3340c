// Every figure of the report layer (heat map, line plot, run plot, paper figures, fit figures),
// drawn as SVG from a stand-in input and from the same input that does not say it is one: the
// stand-in mark exactly on the first, every axis in the unit the units table gives.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "campaign/campaign_load.hpp"
#include "campaign/sweep.hpp"
#include "fit/fit.hpp"
#include "fit/fit_load.hpp"
#include "observe/simulate.hpp"
#include "report/fit_writer.hpp"
#include "report/heatmap.hpp"
#include "report/line_plot.hpp"
#include "report/paper_figures.hpp"
#include "report/run_writer.hpp"
#include "scene/load.hpp"
#include "support_figures.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

namespace {

const fs::path kData = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data";

// `from` copied to `to`, every experiment.yaml's description replaced: a stand-in's or a
// measurement's (the same numbers; only what the data say of themselves differs).
void copy_as(const fs::path& from, const fs::path& to, bool stand_in) {
  fs::create_directories(to);
  fs::copy(from, to, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  for (const auto& e : fs::recursive_directory_iterator(to)) {
    if (e.path().filename() != "experiment.yaml") continue;
    std::string text = slurp(e.path()), out;
    std::size_t at = 0;
    for (std::size_t nl; (nl = text.find('\n', at)) != std::string::npos; at = nl + 1) {
      const std::string line = text.substr(at, nl - at);
      out += line.rfind("description:", 0) == 0 ? (stand_in ? "description: \"STAND-IN, NOT A MEASUREMENT: test copy\""
                                                            : "description: \"test copy, measured\"")
                                                : line;
      out += '\n';
    }
    write_text(e.path(), out + text.substr(at));
  }
}

FigureFormats svg_only() { return FigureFormats{false, true, false}; }

}  // namespace

TEST_CASE("store figures: the mark exactly from stand-ins, axes in the table's units", "[report][figures]") {
  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  for (const bool stand_in : {true, false}) {
    const fs::path w = fresh_dir(stand_in ? "marks_store_standin" : "marks_store_measured");
    copy_as(kData / "scene" / "exp_small", w / "exp", stand_in);
    write_text(w / "scene.yaml",
               "experiment: exp/experiment.yaml\nmodel: {eta: 100, epsilon: 0.9}\n"
               "solver: {method: event, tolerance: 1e-8}\noutput: {series: [t, Q, A]}\n");
    write_text(w / "c.yaml",
               "name: marks\nscenes: [scene.yaml]\nset: {stop.time: 0.3}\ngrids:\n  - name: eta_alpha_b\n    axes:\n"
               "      model.eta: [0, 100]\n      model.alpha_b: {logspace: [0.3e-15, 1.2e-15, 3]}\n");
    SweepOptions o;
    o.out = w / "store";
    o.threads = 1;
    o.quiet = true;
    run_sweep(load_campaign(w / "c.yaml"), o);
    HeatmapOptions h;
    h.x = "model.eta", h.y = "model.alpha_b", h.z = "A0", h.out = w / "heat.svg";
    h.where = {"grid=eta_alpha_b"};
    plot_heatmap(w / "store", h);
    check_figure(w / "heat.svg", stand_in, {"model.eta", "model.alpha_b", "A0"});
    // No internal key names in the title: the grid filter is left out.
    for (const std::string& t : svg_texts(w / "heat.svg")) CHECK(t.find("grid") == std::string::npos);
    LinePlotOptions l;
    l.x = "model.alpha_b", l.y = "A_s", l.out = w / "line.svg";
    l.where = {"model.eta=100"};
    plot_lines(w / "store", l);
    check_figure(w / "line.svg", stand_in, {"model.alpha_b", "A_s"});
    done_with(w);
  }
}

TEST_CASE("run and paper figures: the mark exactly from stand-ins, axes in the table's units", "[report][figures]") {
  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  for (const bool stand_in : {true, false}) {
    const fs::path w = fresh_dir(stand_in ? "marks_run_standin" : "marks_run_measured");
    copy_as(kData / "scene" / "exp_small", w / "exp", stand_in);
    write_text(w / "scene.yaml", "experiment: exp/experiment.yaml\nstop: {time: 0.5}\noutput: {series: [t, Q, A]}\n");
    const Scene scene = load_scene(w / "scene.yaml");
    REQUIRE(is_stand_in(scene.experiment) == stand_in);
    const RunResult r = simulate(scene);
    RunWriteOptions opt;
    opt.plot = true;
    opt.figures = svg_only();
    write_run(w / "run", scene, r.obs, r.recorder, opt);
    check_figure(w / "run" / "plot.svg", stand_in, {"t", "Q", "A"});
    const PaperRun run{scene, r.obs, r.recorder.series(), r.recorder.loading_branch()};
    REQUIRE(write_figure3(w, run, run, svg_only()).empty());
    check_figure(w / "fig3_Q_A_t.svg", stand_in, {"t", "Q", "A"});
    REQUIRE(write_figure4(w, {run}, svg_only()).empty());
    check_figure(w / "fig4_A_Q.svg", stand_in, {"Q", "A"});
    done_with(w);
  }
}

TEST_CASE("fit figures: the mark exactly from stand-ins, axes in the table's units", "[report][figures][fit]") {
  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  for (const bool stand_in : {true, false}) {
    const fs::path w = fresh_dir(stand_in ? "marks_fit_standin" : "marks_fit_measured");
    copy_as(kData / "fit", w / "fit", stand_in);
    const FitSpec spec = load_fit(w / "fit" / "fit.yaml");
    FitOptions options;
    options.threads = 1;
    options.error_bars = true;
    const FitResult result = run_fit(spec, options);
    write_fit(w / "out", spec, result, "", svg_only());
    check_figure(w / "out" / "fitted.svg", stand_in, {"model.alpha_b"});
    for (const char* experiment : {"m010", "m015", "m025"}) {
      const fs::path d = w / "out" / experiment;
      check_figure(d / "convergence.svg", stand_in, {});
      check_figure(d / "profile.svg", stand_in, {"model.alpha_b"});
      check_figure(d / ("AQ_" + std::string(experiment) + ".svg"), stand_in, {"Q", "A"});
    }
    done_with(w);
  }
}
