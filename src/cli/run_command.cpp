// asperity run SCENE.yaml [--out DIR] [--set key=value]... [--quiet] [--plot]
#include <omp.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/options.hpp"
#include "io/numbers.hpp"
#include "io/progress.hpp"
#include "io/warnings.hpp"
#include "observe/simulate.hpp"
#include "report/run_writer.hpp"
#include "scene/load.hpp"
#include "studies/continuum_rule.hpp"

namespace asperity::cli {
namespace {

struct RunOptions {
  std::string scene;
  std::string out;
  std::vector<std::string> overrides;
  bool quiet = false;
  int threads = 0;
  bool plot = false;
  FigureFormats figures;  // of plot.png (--figures)
};

// For independent junctions that have positions: the stiffness error the continuum study's rule
// (studies/continuum_rule.hpp) estimates for this population, and where interactions are
// recommended; "" otherwise.
std::string interaction_advice(const Scene& scene) {
  const JunctionPopulation& J = scene.experiment.junctions;
  if (scene.model.interactions != Interactions::none || J.x_m.size() != J.size()) return "";
  std::vector<double> x = J.x_m, y = J.y_m;
  for (double& v : x) v *= scene.model.position_scale;
  for (double& v : y) v *= scene.model.position_scale;
  const PopulationMeasures m = population_measures(J.area_m2, x, y);
  if (!std::isfinite(m.stiffness_ratio)) return "";
  const StiffnessRule rule = independent_stiffness_rule();
  const double percent = 100 * rule.error_at(m.stiffness_ratio);
  const bool outside = m.stiffness_ratio < rule.ratio_min || m.stiffness_ratio > rule.ratio_max;
  return "independent junctions: estimated stiffness error " +
         io::format_printf(percent < 10 ? "%.2g" : "%.0f", percent) + " %" + (outside ? " (extrapolated)" : "") +
         " at stiffness ratio " + io::format_short(m.stiffness_ratio) + " (coverage " + io::format_short(m.coverage) +
         "; docs/continuum.md, SYNTHETIC surfaces); interactions recommended above ratio " +
         io::format_printf("%.2g", rule.ratio_for(0.05)) + " (error 5 %)";
}

void print_summary(const Scene& scene, const Observables& o, const std::filesystem::path& out) {
  const char* method = scene.solver.method == SolverMethod::reference ? "reference" : "event";
  std::printf("%s: N = %zu, A0 = %.6g mm^2, dt = %.6g us (T0/Ct, Ct = %g), method %s\n", scene.file.string().c_str(),
              o.N, o.A0 * 1e6, o.dt * 1e6, scene.solver.Ct, method);
  std::printf("  Q_s = %.6g N, A_s = %.6g mm^2 (area drop %.3g %%) at t_peak = %.6g s%s\n", o.Q_s, o.A_s * 1e6,
              100.0 * o.area_drop_fraction, o.t_peak,
              o.peak_rule == PeakRule::stick         ? " (peak: closed by a stick after every junction slipped)"
              : o.peak_rule == PeakRule::all_slipped ? " (peak: every junction has slipped)"
              : o.peak_rule == PeakRule::steady_sliding
                  ? " (every junction has slipped, no maximum followed: steady sliding)"
                  : " (no peak: the run ended before every junction had slipped)");
  std::printf("  alpha = %.6g m^2/N^2 (R^2 = %.6f, %zu points), shape exponent n = %.4g\n", o.alpha, o.alpha_R2,
              o.alpha_points, o.shape_exponent);
  if (!std::isnan(o.alpha_measured))
    std::printf("  measured A(Q): alpha = %.6g m^2/N^2 (R^2 = %.6f), shape exponent n = %.4g\n", o.alpha_measured,
                o.alpha_measured_R2, o.shape_exponent_measured);
  if (o.ss_cycles > 0)
    std::printf("  stick-slip: %d cycles, mean drop %.6g N, mean period %.6g s\n", o.ss_cycles, o.ss_drop, o.ss_period);
  else
    std::printf("  stick-slip: no complete cycle (%zu confirmed peaks)\n", o.n_peaks);
  if (const std::string line = interaction_advice(scene); !line.empty()) std::printf("  %s\n", line.c_str());
  std::printf("  max f/(sigma A) = %.6g, t_end = %.6g s, %lld steps, wall %.3f s\n", o.max_f_over_sigmaA, o.t_end,
              static_cast<long long>(o.steps), o.wall_s);
  std::printf("  -> %s\n", out.string().c_str());
}

// Why a run has no static friction peak to report (Q_s = nan), in one line; "" when it has one.
// Q_s is the highest Q after the first slip (recorder.hpp): NaN means no junction slipped.
std::string missing_peak_reason(const Scene& scene, const Observables& o) {
  if (!std::isnan(o.Q_s)) return "";
  const std::string head = scene.file.string() + ": Q_s = nan: ";
  if (o.slips == 0)
    return head + "no junction slipped before the run ended at t = " + io::format_significant(o.t_end) +
           " s (stop.time " + io::format_significant(scene.stop.time) +
           " s); raise stop.time, or check the scene's values and their units";
  return head + "no peak found (" + std::to_string(o.slips) +
         " slips) before the run ended at t = " + io::format_significant(o.t_end) + " s";
}

int run(const RunOptions& opt, const Invocation& inv) {
  const Scene scene = load_scene(opt.scene, opt.overrides);
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  const std::filesystem::path out =
      opt.out.empty() ? std::filesystem::path("results") / "runs" / std::filesystem::path(opt.scene).stem()
                      : std::filesystem::path(opt.out);
  check_run_dir(out);  // fail before the run, not after it
  io::ProgressLine progress("run", "s simulated", scene.stop.time, opt.quiet);
  RunMonitor monitor;
  monitor.period_s = 0.1;
  std::optional<RunResult> result;
  try {
    // Ctrl-C: the run's monitor sees the request within 0.1 s and the run stops, writing nothing.
    const InterruptRequest ctrl_c;
    monitor.poll = [&](double t, double) {
      progress.update(t);
      return !ctrl_c.requested();
    };
    result.emplace(simulate(scene, 0, &monitor));
  } catch (const RunInterrupted& e) {
    std::fprintf(stderr, "%s: %s; nothing written\n", opt.scene.c_str(), e.what());
    return exit_interrupted;
  }
  const RunResult& r = *result;
  write_run(out, scene, r.obs, r.recorder, RunWriteOptions{opt.plot, inv.command_line, opt.figures});
  if (!opt.quiet) print_summary(scene, r.obs, out);
  // A warning, which -q keeps: a result without its peak is one a quiet script must hear of.
  if (const std::string why = missing_peak_reason(scene, r.obs); !why.empty()) io::warn(why);
  return exit_ok;
}

}  // namespace

Command add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand("run",
                                     "Run one scene and write its run directory "
                                     "(series.csv, summary.yaml, scene.yaml)");
  sub->add_option("scene", opt->scene, "Scene YAML file")->required();
  sub->add_option("--out,-o", opt->out, "Run directory (default: results/runs/<scene stem>/)");
  add_set_option(sub, opt->overrides, "in the scene");
  add_threads_option(sub, opt->threads, "OpenMP threads of the reference solver (junctions in parallel from 256 on)");
  add_quiet_flag(sub, opt->quiet);
  sub->add_flag("--plot", opt->plot, "Also write plot.png (Q(t), A(t), A(Q)) with gnuplot");
  add_figures_option(sub, opt->figures);
  return Command{sub, [opt](const Invocation& inv) { return run(*opt, inv); }};
}

}  // namespace asperity::cli
