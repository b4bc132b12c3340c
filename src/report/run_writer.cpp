#include "report/run_writer.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "io/csv.hpp"
#include "io/numbers.hpp"
#include "io/provenance.hpp"
#include "observe/series_csv.hpp"
#include "report/gnuplot.hpp"
#include "report/output_dir.hpp"
#include "report/units.hpp"
#include "scene/input_files.hpp"
#include "scene/load.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

const char* method_name(SolverMethod m) {
  switch (m) {
    case SolverMethod::reference:
      return "reference";
    case SolverMethod::event:
      return "event";
  }
  return "unknown";
}

constexpr const char* kSummaryHeader = "# asperity run summary (SI units: m, m², N, s)";

// A run folder is written by publish_dir: only the files a previous run wrote there (listed in
// its marker with their content) are replaced; anything else in it stays, and a folder without
// such a list is refused.
}  // namespace

void check_run_dir(const fs::path& dir) { check_publishable(dir, "run", "--out"); }  // names the folder as given

std::string yaml_double(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
  return io::format_g17(x);
}

std::string summary_yaml(const Scene& scene, const Observables& o, const std::vector<Peak>& peaks,
                         const std::string& command_line) {
  std::ostringstream y;
  auto d = [&](const char* key, double v) { y << key << ": " << yaml_double(v) << '\n'; };
  y << kSummaryHeader << '\n';
  y << "asperity_version: " << io::yaml_quoted(io::build_info().version) << '\n';
  y << "scene_file: " << io::yaml_quoted(scene.file.string()) << '\n';
  y << "experiment: " << io::yaml_quoted(scene.experiment.name) << '\n';
  y << "method: " << method_name(scene.solver.method) << '\n';
  d("Ct", scene.solver.Ct);
  d("tolerance", scene.solver.tolerance);
  // Only with interactions: the summaries of independent runs keep their keys.
  if (scene.model.interactions != Interactions::none) d("interaction_tolerance", scene.solver.interaction_tolerance);
  for (const ObservableField& f : observable_fields()) {
    y << f.name << ": " << observable_text(f, o, yaml_double);
    if (f.kind == ObservableKind::label) y << "  # how the first peak was found (README: The static friction peak)";
    y << '\n';
  }
  // Confirmed peaks of Q and the trough after each (the stick-slip cycles).
  if (peaks.empty()) {
    y << "peaks: []\n";
  } else {
    y << "peaks:\n";
    for (const auto& p : peaks)
      y << "  - {t_max: " << yaml_double(p.max.t) << ", Q_max: " << yaml_double(p.max.Q)
        << ", A_max: " << yaml_double(p.max.A) << ", t_min: " << yaml_double(p.min.t)
        << ", Q_min: " << yaml_double(p.min.Q) << ", A_min: " << yaml_double(p.min.A) << "}\n";
  }
  y << io::provenance_yaml(command_line, input_files(scene));
  return y.str();
}

void write_run(const fs::path& dir, const Scene& scene, const Observables& obs, const Recorder& rec,
               const RunWriteOptions& opt) {
  publish_dir(dir, "run", "--out", [&](const fs::path& tmp) {
    // Text first: a failure (e.g. scene_to_yaml throwing) happens before anything is written.
    const std::string scene_text = scene_to_yaml(scene);
    const std::string summary_text = summary_yaml(scene, obs, rec.peaks(), opt.command_line);
    if (!scene.output.series.empty()) {
      std::ostringstream csv;
      write_series_csv(csv, rec.series(), scene.output.series);
      io::write_text_file(tmp / "series.csv", csv.str());
    }
    io::write_text_file(tmp / "summary.yaml", summary_text);
    io::write_text_file(tmp / "scene.yaml", scene_text);
    if (opt.plot) {
      std::string error;
      if (!write_run_plot(tmp, &error, opt.figures, is_stand_in(scene.experiment)))
        std::fprintf(stderr, "%s: plot.png not drawn: %s (plot.gp is kept: `gnuplot plot.gp` in the run folder)\n",
                     dir.string().c_str(), error.c_str());
    }
  });
}

bool write_run_plot(const fs::path& dir, std::string* error, const FigureFormats& formats, bool stand_in) {
  const fs::path csv = dir / "series.csv";
  std::ifstream in(csv);
  std::string header;
  if (!in || !std::getline(in, header)) return false;
  std::vector<std::string> cols;
  try {
    cols = io::csv_split(header);
  } catch (const std::runtime_error&) {
    return false;
  }
  auto col = [&](const std::string& n) -> int {
    const auto it = std::find(cols.begin(), cols.end(), n);
    return it == cols.end() ? -1 : static_cast<int>(it - cols.begin()) + 1;  // gnuplot: 1-based
  };
  const int ct = col("t"), cq = col("Q"), ca = col("A");
  if (ct < 0 || cq < 0 || ca < 0) {
    if (error) *error = "the series has no t, Q and A columns (output.series)";
    return false;
  }
  const std::string t = std::to_string(ct), q = std::to_string(cq), a = std::to_string(ca);
  // Labels and the area's unit (mm²) from the units table, as every figure.
  const auto label = [](const char* column) { return gnuplot_quote(axis_markup(column)); };
  const std::string area = "($" + a + "*" + io::format_double(figure_unit("A").scale) + ")";
  // Three panels stacked: each with few tics (tics_for_span), or a journal column's height and
  // width overlap them.
  const auto tics = [](const std::string& x, const std::string& y) {
    return tics_for_span("x", "'series.csv' skip 1", x) + tics_for_span("y", "'series.csv' skip 1", y);
  };
  std::ostringstream gp;
  gp << "set datafile separator ','\n"
     << stand_in_mark(stand_in) << "set key off\n"
     << "set grid\n"
     << "set multiplot layout 3,1\n"
     << "set xlabel " << label("t") << "\nset ylabel " << label("Q") << "\n"
     << tics(t, q) << "plot 'series.csv' skip 1 using " << t << ":" << q << " with lines lw 1.5\n"
     << "set ylabel " << label("A") << "\n"
     << tics(t, area) << "plot 'series.csv' skip 1 using " << t << ":" << area << " with lines lw 1.5\n"
     << "set xlabel " << label("Q") << "\nset ylabel " << label("A") << "\n"
     << tics(q, area) << "plot 'series.csv' skip 1 using " << q << ":" << area << " with lines lw 1.5\n"
     << "unset multiplot\n";
  return render_figures(dir / "plot.png", gp.str(), 900, 1000, formats, error);
}

}  // namespace asperity
