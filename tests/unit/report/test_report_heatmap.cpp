// report/heatmap.hpp: the heat map of a sweep store, one cell per grid point.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "campaign/campaign_load.hpp"
#include "campaign/sweep.hpp"
#include "io/csv.hpp"
#include "report/heatmap.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using Catch::Matchers::Contains;

namespace {

const fs::path& kData = asperity::testing::kCampaignData;

fs::path temp_dir() { return asperity::testing::numbered_dir("asperity_heatmap"); }
using asperity::testing::slurp;

using asperity::testing::lines_of;

SweepReport sweep(const Campaign& c, const fs::path& out, int threads) {
  SweepOptions o;
  o.out = out;
  o.threads = threads;
  o.quiet = true;
  return run_sweep(c, o);
}

}  // namespace

TEST_CASE("plot draws a PNG heat map with one cell per grid point and blanks for NaN", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  const fs::path d = temp_dir();
  sweep(c, d / "s", 2);
  // Independent count of the blank cells: eta_eps rows whose ss_drop is not a finite number.
  const auto rows = lines_of(slurp(d / "s" / "points.csv"));
  const auto header = io::csv_split(rows[0]);
  const std::size_t col = static_cast<std::size_t>(std::find(header.begin(), header.end(), "ss_drop") - header.begin());
  std::size_t nan_cells = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto f = io::csv_split(rows[i]);
    if (f[2] == "eta_eps" && (f[col] == "nan" || f[col].empty())) ++nan_cells;
  }
  HeatmapOptions o;
  o.x = "model.eta";
  o.y = "model.epsilon";
  o.z = "ss_drop";
  const HeatmapReport r = plot_heatmap(d / "s", o);
  CHECK(r.cells == 9);  // 3 eta × 3 epsilon (the mass grid does not vary both)
  CHECK(r.used_grid == "eta_eps");
  CHECK(r.blank == nan_cells);
  CHECK(slurp(r.png).substr(1, 3) == "PNG");
  o.z = "no_such_column";
  CHECK_THROWS_WITH(plot_heatmap(d / "s", o), Contains("no column 'no_such_column'"));
  // Over eta × mass both grids contribute points on the same cells: asks for a filter.
  o.z = "Q_s";
  o.y = "experiment.mass";
  CHECK_THROWS_WITH(plot_heatmap(d / "s", o), Contains("--where"));
}
