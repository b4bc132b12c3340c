// asperity fit FIT.yaml [--out DIR] [--threads N] [--no-profile] [--no-error-bars] [--quiet]
#include <atomic>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "io/progress.hpp"
#include "fit/fit.hpp"
#include "report/fit_writer.hpp"
#include "fit/fit_load.hpp"

namespace asperity::cli {
namespace {

struct FitCliOptions {
  std::string fit_file;
  std::string out;
  int threads = 0;  // all hardware threads
  std::vector<std::string> overrides;
  bool no_profile = false;
  bool no_error_bars = false;
  bool quiet = false;
};

int run(const FitCliOptions& opt, const Invocation& inv) {
  const FitSpec spec = load_fit(opt.fit_file, opt.overrides);
  const std::filesystem::path out =
      opt.out.empty() ? std::filesystem::path("results") / "fits" / spec.name : std::filesystem::path(opt.out);
  check_fit_dir(out);  // fail before the fit, not after it
  FitOptions fo;
  fo.threads = threads_or_all(opt.threads);
  fo.profile = !opt.no_profile;
  fo.error_bars = !opt.no_error_bars;
  if (!opt.quiet) {
    std::printf("%s: %s, %zu experiment(s)%s, %s, %d thread(s)\n", opt.fit_file.c_str(), objective_name(spec.objective),
                spec.experiments.size(), spec.separate ? " fitted separately" : " fitted jointly", spec.algorithm.c_str(),
                threads_or_all(opt.threads));
    std::fflush(stdout);
    fo.progress = [](const std::string& line) {
      std::printf("  %s\n", line.c_str());
      std::fflush(stdout);
    };
  }
  // Evaluations against the budget (an optimization may stop earlier: the ETA is an upper bound).
  const std::size_t optimizations = spec.separate ? spec.experiments.size() : 1;
  ProgressLine progress("fit", "evaluations (budget)", static_cast<double>(spec.max_evaluations) * static_cast<double>(optimizations), opt.quiet);
  std::atomic<int> evaluated{0};
  std::mutex best_mutex;
  double best = HUGE_VAL;
  fo.on_evaluation = [&](double objective) {
    double b;
    {
      const std::lock_guard<std::mutex> lock(best_mutex);
      if (objective < best) best = objective;
      b = best;
    }
    char text[64];
    std::snprintf(text, sizeof text, "best objective %.4g", b);
    progress.update(++evaluated, text);
  };
  const FitResult result = run_fit(spec, fo);
  write_fit(out, spec, result, inv.command_line);
  int evaluations = 0;
  bool ok = true;
  for (const auto& o : result.fits) {
    evaluations += o.evaluations;
    ok = ok && o.ok();
  }
  if (!opt.quiet)
    std::printf("  %d evaluations in %zu fit(s); optimizations %.3f s (sum), total wall %.3f s (incl. profile, error-bar refits)\n  -> %s\n",
                evaluations, result.fits.size(), result.fit_wall_s, result.wall_s, out.string().c_str());
  if (!ok) {
    for (const auto& o : result.fits)
      if (!o.ok()) std::cerr << "fit " << o.label << " failed: " << o.failure << '\n';
    return exit_failure;
  }
  return exit_ok;
}

}  // namespace

Command add_fit_command(CLI::App& app) {
  auto opt = std::make_shared<FitCliOptions>();
  CLI::App* sub = app.add_subcommand("fit", "Calibrate model parameters against measurements with NLopt "
                                            "(writes results/fits/<name>/)");
  sub->add_option("fit", opt->fit_file, "Fit YAML file (see fits/)")->required();
  sub->add_option("--out,-o", opt->out, "Results directory (default: results/fits/<name>/)");
  add_threads_option(sub, opt->threads, "Worker threads (experiments or per-experiment fits in parallel)");
  add_set_option(sub, opt->overrides, "in every experiment's scene (the fit's parameters and the objective's own settings win)");
  sub->add_flag("--no-profile", opt->no_profile, "Skip the objective profile around the optimum");
  sub->add_flag("--no-error-bars", opt->no_error_bars, "Skip the error-bar refits");
  add_quiet_flag(sub, opt->quiet);
  return Command{sub, [opt](const Invocation& inv) { return run(*opt, inv); }};
}

}  // namespace asperity::cli
