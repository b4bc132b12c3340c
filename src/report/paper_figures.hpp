#pragma once
// The paper reproduction's figures and table (main job), from runs held in memory.
//   fig3_Q_A_t.png  analogue of the paper's Figure 3: Q(t) and A(t) for the smallest and the
//                   largest load, model against the (stand-in) measurement;
//   fig4_A_Q.png    analogue of Figure 4: A(Q) of every load, model loading branch against the
//                   measured samples, absolute and normalised (A/A0 against Q/Q_s).
//   table.csv       N, A0, dt, Q_s, A_s, t_peak, alpha, shape exponents, area drop, stick-slip.
// A measured curve holds A(Q) only, without time: for Figure 3 its samples are placed at the
// model's time of equal Q on the loading branch (said on the figure).
#include <filesystem>
#include <string>
#include <vector>

#include "observe/observables.hpp"
#include "report/gnuplot.hpp"  // FigureFormats
#include "scene/scene.hpp"
#include "solve/core/observer.hpp"

namespace asperity {

struct PaperRun {
  Scene scene;
  Observables obs;
  std::vector<Sample> series;   // every sample (t, Q, A needed)
  std::vector<Sample> loading;  // loading branch up to the first peak
};

// Time at which the loading branch first reaches Q (linear interpolation); NaN beyond it.
double loading_time_at(const std::vector<Sample>& loading, double Q);

// Each figure carries the stand-in mark (report/gnuplot.hpp) when any run's experiment is a
// stand-in (is_stand_in). Each returns "" when drawn, else why not (gnuplot missing or failing);
// the script is kept beside the PNG either way. Each figure in every format of `formats`
// (fig3_Q_A_t.svg, .pdf: report/gnuplot.hpp).
std::string write_figure3(const std::filesystem::path& out_dir, const PaperRun& smallest, const PaperRun& largest,
                          const FigureFormats& formats = {});
std::string write_figure4(const std::filesystem::path& out_dir, const std::vector<PaperRun>& runs,
                          const FigureFormats& formats = {});
// table.csv: a header line (kPaperTableHeader), then one row per run (names CSV-quoted).
std::string paper_table_csv(const std::vector<PaperRun>& runs);
inline constexpr const char* kPaperTableHeader =
    "experiment,N,A0_m2,dt_s,Q_s_N,A_s_m2,t_peak_s,alpha_m2_per_N2,alpha_R2,alpha_measured_m2_per_N2,"
    "shape_exponent,shape_exponent_measured,area_drop_fraction,ss_cycles,ss_drop_N,ss_period_s";

}  // namespace asperity
