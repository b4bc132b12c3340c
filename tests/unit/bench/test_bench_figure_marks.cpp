// The bench figures (savings.png, work_precision.png) drawn as SVG from rows measured on a
// stand-in and on an experiment that is not one: the stand-in mark exactly on the first.
#include <catch2/catch.hpp>
#include <filesystem>

#include "bench/savings.hpp"
#include "bench/tradeoff.hpp"
#include "support_figures.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

TEST_CASE("bench figures: the mark exactly from stand-ins", "[bench][figures]") {
  if (!io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to draw");
    return;
  }
  const FigureFormats svg{false, true, false};
  for (const bool stand_in : {true, false}) {
    const fs::path w = fresh_dir(stand_in ? "bench_marks_standin" : "bench_marks_measured");
    SavingRow base, variant;
    base.experiment = variant.experiment = "P4.00N";
    base.saving = variant.saving = "series";
    base.variant = "all series", variant.variant = "output.series=[]";
    base.baseline = true;
    base.stand_in = variant.stand_in = stand_in;
    base.cpu_s = 0.02, variant.cpu_s = 0.01;
    write_savings(w, {base, variant}, svg);
    check_figure(w / "savings.svg", stand_in, {});
    TradeoffResult r;
    r.stand_in = stand_in;
    for (const char* method : {"reference", "event"})
      for (const double setting : {1.0, 2.0}) {
        WorkPrecisionRow row;
        row.experiment = "P0.20N", row.method = method, row.setting = setting, row.wall_s = setting;
        row.error.fill(1e-3 / setting);
        r.rows.push_back(row);
      }
    write_tradeoff(w, r, svg);
    check_figure(w / "work_precision.svg", stand_in, {});
    done_with(w);
  }
}
