#include "report/paper_figures.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "io/csv.hpp"
#include "io/numbers.hpp"
#include "report/gnuplot.hpp"
#include "report/units.hpp"

namespace asperity {
namespace fs = std::filesystem;

double loading_time_at(const std::vector<Sample>& loading, double Q) {
  for (std::size_t i = 1; i < loading.size(); ++i) {
    const Sample& a = loading[i - 1];
    const Sample& b = loading[i];
    if (a.Q <= Q && Q <= b.Q) {
      const double f = b.Q > a.Q ? (Q - a.Q) / (b.Q - a.Q) : 0.0;
      return a.t + f * (b.t - a.t);
    }
  }
  if (!loading.empty() && Q == loading.front().Q) return loading.front().t;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

// The axis label of a series column in its figure unit (A in mm², report/units.hpp).
std::string label_of(const char* column) { return gnuplot_quote(axis_markup(column)); }
double area_scale() { return figure_unit("A").scale; }

bool any_stand_in(const std::vector<const PaperRun*>& runs) {
  for (const PaperRun* r : runs)
    if (is_stand_in(r->scene.experiment)) return true;
  return false;
}

std::vector<std::vector<double>> series_rows(const std::vector<Sample>& s) {
  std::vector<std::vector<double>> rows;
  rows.reserve(s.size());
  for (const Sample& x : s) rows.push_back({x.t, x.Q, x.A * area_scale()});
  return rows;
}

// Measured samples as (t at equal model Q, Q, A in its figure unit).
std::vector<std::vector<double>> measured_rows(const PaperRun& r) {
  std::vector<std::vector<double>> rows;
  if (!r.scene.experiment.measured) return rows;
  const auto& m = *r.scene.experiment.measured;
  for (std::size_t i = 0; i < m.Q_N.size(); ++i)
    rows.push_back({loading_time_at(r.loading, m.Q_N[i]), m.Q_N[i], m.A_m2[i] * area_scale()});
  return rows;
}

// The PNGs' 10-point text (their layout is made for it); SVG and PDF keep their journal size.
constexpr const char* kScreenFont = "if (GPVAL_TERM eq 'pngcairo') set termoption font ',10'\n";

const char* kColors[] = {"#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02", "#a6761d", "#666666"};

}  // namespace

std::string write_figure3(const fs::path& out_dir, const PaperRun& small, const PaperRun& large,
                          const FigureFormats& formats) {
  std::ostringstream gp;
  gp << gnuplot_block("ms", series_rows(small.series)) << gnuplot_block("me", measured_rows(small))
     << gnuplot_block("ls", series_rows(large.series)) << gnuplot_block("le", measured_rows(large));
  gp << kScreenFont << stand_in_mark(any_stand_in({&small, &large})) << "set grid\n"
     << "set multiplot layout 2,2 title "
     << gnuplot_text(
            "Figure 3 analogue. Measured A(Q) has no time axis: its samples sit at the model time of equal Q "
            "(loading branch).")
     << "\n";
  auto panel = [&](const PaperRun& r, const char* model, const char* meas, bool area) {
    // Q rises from the lower left, A falls from the upper left (the measured points start
    // there): each key sits in the corner its curves leave empty.
    gp << "set title " << gnuplot_text(r.scene.experiment.name + " (N = " + std::to_string(r.obs.N) + ")") << "\n"
       << "set key " << (area ? "bottom left" : "top left") << " Left reverse opaque box\n"
       << "set xlabel " << label_of("t") << "\nset ylabel " << label_of(area ? "A" : "Q") << "\n"
       << "plot $" << model << " using 1:" << (area ? 3 : 2) << " with lines lw 1.5 lc rgb '#1f4e9a' title 'model'";
    if (area && r.scene.experiment.measured)
      gp << ", $" << meas << " using 1:3 with points pt 7 ps 0.6 lc rgb '#d95f02' title 'measured'";
    gp << "\n";
  };
  panel(small, "ms", "me", false);
  panel(large, "ls", "le", false);
  panel(small, "ms", "me", true);
  panel(large, "ls", "le", true);
  gp << "unset multiplot\n";
  std::string error;
  if (!render_figures(out_dir / "fig3_Q_A_t.png", gp.str(), 1200, 900, formats, &error)) return error;
  return "";
}

std::string write_figure4(const fs::path& out_dir, const std::vector<PaperRun>& runs, const FigureFormats& formats) {
  std::ostringstream gp;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const PaperRun& r = runs[k];
    std::vector<std::vector<double>> model, meas;
    for (const Sample& s : r.loading) model.push_back({s.Q, s.A * area_scale(), s.Q / r.obs.Q_s, s.A / r.obs.A0});
    if (r.scene.experiment.measured) {
      const auto& m = *r.scene.experiment.measured;
      for (std::size_t i = 0; i < m.Q_N.size(); ++i)
        meas.push_back({m.Q_N[i], m.A_m2[i] * area_scale(), m.Q_N[i] / r.obs.Q_s, m.A_m2[i] / r.obs.A0});
    }
    const std::string id = std::to_string(k);
    gp << gnuplot_block(std::string("m").append(id), model) << gnuplot_block(std::string("e").append(id), meas);
  }
  std::vector<const PaperRun*> all;
  for (const PaperRun& r : runs) all.push_back(&r);
  gp << kScreenFont << stand_in_mark(any_stand_in(all)) << "set grid\nset key outside right\n"
     << "set multiplot layout 1,2 title "
     << gnuplot_text("Figure 4 analogue. Lines: model loading branch; points: measured.") << "\n";
  for (int panel = 0; panel < 2; ++panel) {
    const int cx = panel == 0 ? 1 : 3, cy = panel == 0 ? 2 : 4;
    gp << (panel == 0 ? "set xlabel " + label_of("Q") + "\nset ylabel " + label_of("A") + "\nset title 'A(Q)'\n"
                      : std::string("set xlabel 'Q/Q_s [1]'\nset ylabel 'A/A_0 [1]'\nset title 'normalised: a "
                                    "straight line is quasi-linear, a parabola quadratic'\n"));
    gp << "plot ";
    for (std::size_t k = 0; k < runs.size(); ++k) {
      const char* col = kColors[k % 8];
      if (k) gp << ", ";
      gp << "$m" << k << " using " << cx << ":" << cy << " with lines lw 2 lc rgb '" << col << "' title "
         << gnuplot_text(runs[k].scene.experiment.name);
      if (runs[k].scene.experiment.measured)
        gp << ", $e" << k << " using " << cx << ":" << cy << " with points pt 7 ps 0.4 lc rgb '" << col << "' notitle";
    }
    gp << "\n";
  }
  gp << "unset multiplot\n";
  std::string error;
  if (!render_figures(out_dir / "fig4_A_Q.png", gp.str(), 1300, 600, formats, &error)) return error;
  return "";
}

std::string paper_table_csv(const std::vector<PaperRun>& runs) {
  std::ostringstream s;
  s << kPaperTableHeader << '\n';
  for (const PaperRun& r : runs) {
    const Observables& o = r.obs;
    s << io::csv_field(r.scene.experiment.name) << ',' << o.N << ',' << io::format_g17(o.A0) << ','
      << io::format_g17(o.dt) << ',' << io::format_g17(o.Q_s) << ',' << io::format_g17(o.A_s) << ','
      << io::format_g17(o.t_peak) << ',' << io::format_g17(o.alpha) << ',' << io::format_g17(o.alpha_R2) << ','
      << io::format_g17(o.alpha_measured) << ',' << io::format_g17(o.shape_exponent) << ','
      << io::format_g17(o.shape_exponent_measured) << ',' << io::format_g17(o.area_drop_fraction) << ',' << o.ss_cycles
      << ',' << io::format_g17(o.ss_drop) << ',' << io::format_g17(o.ss_period) << '\n';
  }
  return s.str();
}

}  // namespace asperity
