// asperity reproduce SCENE.yaml... [--out results/paper] [--set key=value]... [--threads N] [--quiet]
// The paper reproduction (main job): runs every scene (in parallel), writes one run directory
// per scene, the analogues of the paper's Figures 3 and 4, and table.csv.

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include "batch/parallel_runner.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "fit/fit.hpp"
#include "fit/fit_load.hpp"
#include "io/atomic_file.hpp"
#include "io/progress.hpp"
#include "observe/simulate.hpp"
#include "report/output_dir.hpp"
#include "report/paper_figures.hpp"
#include "report/run_writer.hpp"
#include "scene/load.hpp"
#include "studies/claims.hpp"

namespace asperity::cli {
namespace {

struct ReproduceOptions {
  std::vector<std::string> scenes;
  std::string out = "results/paper";
  std::vector<std::string> overrides;
  int threads = 0;
  bool quiet = false;
  bool claims = true;
  std::string fit;        // per-load α_b calibration for claim 5 (e.g. fits/paper_alpha_b.yaml)
  FigureFormats figures;  // of Figures 3 and 4 (--figures)
};

// The calibration fit of claim 5 (`--fit`), checked before any run.
FitSpec calibration_spec(const std::string& fit) {
  if (fit.empty()) return {};
  FitSpec spec = load_fit(fit);
  if (spec.objective != FitObjective::quadratic_alpha || !spec.separate || spec.parameters.size() != 1 ||
      spec.parameters.front().key != "model.alpha_b")
    throw io::InputError(fit, 0, "",
                         "reproduce --fit needs a per-experiment (separate) quadratic_alpha fit of "
                         "model.alpha_b alone, like fits/paper_alpha_b.yaml");
  return spec;
}

// The run folder of each scene in `out` (refused when two collide or one is not ours).
std::vector<std::filesystem::path> run_dirs(const std::vector<std::string>& scenes, const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  std::vector<fs::path> dirs;
  for (const auto& s : scenes) {
    dirs.push_back(out / fs::path(s).stem());
    if (std::count(dirs.begin(), dirs.end(), dirs.back()) > 1)
      throw io::InputError(s, 0, "",
                           "two scenes share the file name " + fs::path(s).filename().string() +
                               ": their run folders in " + out.string() + " would collide");
    check_run_dir(dirs.back());
  }
  return dirs;
}

// Every paper run (in parallel), each written to its folder; SolverError names the first that failed.
void run_paper(std::vector<PaperRun>& runs, const std::vector<std::filesystem::path>& dirs, const ReproduceOptions& opt,
               const Invocation& inv, int threads) {
  std::vector<std::string> errors(runs.size());
  io::ProgressLine progress("reproduce", "runs", static_cast<double>(runs.size()), opt.quiet);
  ParallelRunner(threads).for_each(
      runs.size(),
      [&](std::size_t i) {
        try {
          RunResult r = simulate(runs[i].scene);
          write_run(dirs[i], runs[i].scene, r.obs, r.recorder, RunWriteOptions{false, inv.command_line, {}});
          runs[i].obs = r.obs;
          runs[i].series = r.recorder.series();
          runs[i].loading = r.recorder.loading_branch();
        } catch (const std::exception& e) {
          errors[i] = e.what();
        }
      },
      [&](std::size_t finished, std::size_t) { progress.update(static_cast<double>(finished)); });
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (!errors[i].empty()) throw SolverError(opt.scenes[i] + ": " + errors[i]);
}

// table.csv and Figures 3 and 4 (a figure gnuplot could not draw is said, its script kept).
void write_paper_outputs(const std::filesystem::path& out, const std::vector<PaperRun>& runs,
                         const FigureFormats& figures) {
  std::filesystem::remove(out / "REPORT.md");  // a previous one would describe other runs
  io::write_text_file(out / "table.csv", paper_table_csv(runs));
  if (runs.empty()) return;
  for (const auto& [name, error] :
       {std::pair<const char*, std::string>{"fig3_Q_A_t.png", write_figure3(out, runs.front(), runs.back(), figures)},
        {"fig4_A_Q.png", write_figure4(out, runs, figures)}})
    if (!error.empty())
      std::fprintf(stderr, "reproduce: %s not drawn: %s (its script, data inline, is kept beside it)\n", name,
                   error.c_str());
}

// Claim 5's per-load calibration (run_fit); adds its evaluations to `runs_count`.
Calibration calibrate(const FitSpec& spec, const std::string& fit_file, int threads, bool quiet,
                      std::size_t& runs_count) {
  Calibration calibration;
  calibration.fit_file = fit_file;
  FitOptions fo;
  fo.threads = threads;
  fo.profile = false;
  fo.error_bars = false;
  io::ProgressLine fp("reproduce", "calibration evaluations (at most)", static_cast<double>(fit_run_budget(spec, fo)),
                      quiet);
  std::atomic<int> evaluations{0};  // a finished calibration adds what it left of its budget
  fo.on_evaluation = [&](const FitTick& t) { fp.update(evaluations += t.counted()); };
  const FitResult fr = run_fit(spec, fo);
  for (const Optimization& f : fr.fits) {
    // A failed calibration stays in the report as failed: claim 5 then has no evidence at that load.
    CalibratedRun c;
    c.experiment = f.label;
    if (!f.ok() || f.best_runs.empty() || f.best.empty()) {
      c.failure = f.failure.empty() ? std::string("no successful evaluation") : f.failure;
      std::fprintf(stderr, "calibration %s failed: %s\n", f.label.c_str(), c.failure.c_str());
    } else {
      c.alpha_b = f.best.front();
      c.obs = f.best_runs.front().obs;
      c.loading = f.best_runs.front().loading;
      c.evaluations = f.evaluations;
      c.stop_reason = f.stop_reason;
    }
    calibration.runs.push_back(std::move(c));
  }
  runs_count += static_cast<std::size_t>(std::accumulate(
      fr.fits.begin(), fr.fits.end(), 0, [](int a, const Optimization& f) { return a + f.evaluations; }));
  return calibration;
}

// REPORT.md: the claim variants (and the calibration) run, then judged; returns the runs made.
std::size_t write_claims(const std::filesystem::path& out, const std::vector<PaperRun>& runs,
                         const FitSpec& spec_of_fit, const ReproduceOptions& opt, int threads,
                         const std::string& label) {
  std::vector<Scene> base;
  for (const auto& r : runs) base.push_back(r.scene);
  io::ProgressLine vp("reproduce", "claim-variant runs", 0, opt.quiet);
  const auto variants = run_variants(base, paper_claim_variants(), threads, [&](std::size_t done, std::size_t total) {
    vp.set_total(static_cast<double>(total));
    vp.update(static_cast<double>(done));
  });
  std::size_t n_runs = variants.size();
  const Calibration calibration =
      opt.fit.empty() ? Calibration{} : calibrate(spec_of_fit, opt.fit, threads, opt.quiet, n_runs);
  io::write_text_file(out / "REPORT.md", claims_report(runs, variants, calibration, label));
  return n_runs;
}

void print_summary(const std::vector<PaperRun>& runs, bool standin) {
  std::printf("%-8s %6s %10s %10s %9s %12s %7s %6s %10s %10s %7s\n", "exp", "N", "Q_s [N]", "A_s [mm2]", "t_peak",
              "alpha", "n", "n_meas", "ss_drop", "ss_period", "wall");
  for (const auto& r : runs) {
    const auto& o = r.obs;
    std::printf("%-8s %6zu %10.5g %10.5g %9.4g %12.5g %7.3g %6.3g %10.4g %10.4g %6.2fs\n",
                r.scene.experiment.name.c_str(), o.N, o.Q_s, o.A_s * 1e6, o.t_peak, o.alpha, o.shape_exponent,
                o.shape_exponent_measured, o.ss_drop, o.ss_period, o.wall_s);
  }
  if (standin) std::printf("STAND-IN data: these numbers are not properties of the real experiments.\n");
}

int reproduce(const ReproduceOptions& opt, const Invocation& inv) {
  namespace fs = std::filesystem;
  const auto t0 = std::chrono::steady_clock::now();
  // Load everything first: a bad scene fails before any run.
  std::vector<PaperRun> runs(opt.scenes.size());
  for (std::size_t i = 0; i < opt.scenes.size(); ++i) runs[i].scene = load_scene(opt.scenes[i], opt.overrides);
  const FitSpec spec_of_fit = calibration_spec(opt.fit);
  const fs::path out(opt.out);
  // Only into a new or empty folder, or one reproduce wrote (before markers: its table.csv).
  check_ours(out, "reproduce", "--out",
             [](const fs::path& d) { return first_line_is(d / "table.csv", kPaperTableHeader); });
  const std::vector<fs::path> dirs = run_dirs(opt.scenes, out);
  fs::create_directories(out);
  write_marker(out, "reproduce");
  const int threads = threads_or_all(opt.threads);
  run_paper(runs, dirs, opt, inv, threads);
  // Figures and table in load order (smallest load first when the scenes are named so).
  std::sort(runs.begin(), runs.end(), [](const PaperRun& a, const PaperRun& b) {
    return a.scene.experiment.junctions.size() < b.scene.experiment.junctions.size();
  });
  bool standin = false;
  for (const auto& r : runs) standin = standin || r.scene.experiment.description.find("STAND-IN") != std::string::npos;
  const std::string label = standin ? "STAND-IN data, not measurements" : "";
  write_paper_outputs(out, runs, opt.figures);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double wall_claims = 0;
  std::size_t n_variant_runs = 0;
  if (opt.claims && !runs.empty()) {
    const auto t1 = std::chrono::steady_clock::now();
    n_variant_runs = write_claims(out, runs, spec_of_fit, opt, threads, label);
    wall_claims = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  }
  if (!opt.quiet) {
    print_summary(runs, standin);
    std::printf("%zu runs on %d threads in %.2f s wall -> %s (table.csv, fig3_Q_A_t.png, fig4_A_Q.png)\n", runs.size(),
                threads, wall, out.string().c_str());
    if (opt.claims)
      std::printf("claims: %zu more runs in %.1f s wall -> %s\n", n_variant_runs, wall_claims,
                  (out / "REPORT.md").string().c_str());
  }
  return exit_ok;
}

}  // namespace

Command add_reproduce_command(CLI::App& app) {
  auto opt = std::make_shared<ReproduceOptions>();
  CLI::App* sub = app.add_subcommand("reproduce",
                                     "Paper reproduction: run scenes in parallel, write run "
                                     "directories, Figures 3 and 4 and table.csv");
  sub->add_option("scenes", opt->scenes, "Scene YAML files (e.g. scenes/paper/*.yaml)")->required();
  sub->add_option("--out,-o", opt->out, "Output directory (default results/paper)");
  add_set_option(sub, opt->overrides, "in every scene");
  add_threads_option(sub, opt->threads, "Runs in parallel");
  add_quiet_flag(sub, opt->quiet);
  add_figures_option(sub, opt->figures);
  sub->add_flag("!--no-claims", opt->claims, "Skip the claim variants and REPORT.md");
  sub->add_option("--fit", opt->fit, "Per-load alpha_b calibration for claim 5 (e.g. fits/paper_alpha_b.yaml)");
  return Command{sub, [opt](const Invocation& inv) { return reproduce(*opt, inv); }};
}

}  // namespace asperity::cli
