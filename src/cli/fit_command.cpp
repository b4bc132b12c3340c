// asperity fit FIT.yaml [--out DIR] [--threads N] [--no-profile] [--no-error-bars] [--quiet]
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "fit/fit.hpp"
#include "report/fit_writer.hpp"
#include "fit/fit_load.hpp"

namespace asperity::cli {
namespace {

struct FitCliOptions {
  std::string fit_file;
  std::string out;
  int threads = 2;
  bool no_profile = false;
  bool no_error_bars = false;
  bool quiet = false;
};

int run(const FitCliOptions& opt, const Invocation& inv) {
  const FitSpec spec = load_fit(opt.fit_file);
  const std::filesystem::path out =
      opt.out.empty() ? std::filesystem::path("results") / "fits" / spec.name : std::filesystem::path(opt.out);
  check_fit_dir(out);  // fail before the fit, not after it
  FitOptions fo;
  fo.threads = opt.threads;
  fo.profile = !opt.no_profile;
  fo.error_bars = !opt.no_error_bars;
  if (!opt.quiet) {
    std::printf("%s: %s, %zu experiment(s)%s, %s, %d thread(s)\n", opt.fit_file.c_str(), objective_name(spec.objective),
                spec.experiments.size(), spec.separate ? " fitted separately" : " fitted jointly", spec.algorithm.c_str(),
                opt.threads);
    std::fflush(stdout);
    fo.progress = [](const std::string& line) {
      std::printf("  %s\n", line.c_str());
      std::fflush(stdout);
    };
  }
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
  sub->add_option("--threads,-j", opt->threads, "Worker threads (experiments or per-experiment fits in parallel)")
      ->check(CLI::Range(1, 256));
  sub->add_flag("--no-profile", opt->no_profile, "Skip the objective profile around the optimum");
  sub->add_flag("--no-error-bars", opt->no_error_bars, "Skip the error-bar refits");
  sub->add_flag("--quiet,-q", opt->quiet, "Print nothing on success");
  return Command{sub, [opt](const Invocation& inv) { return run(*opt, inv); }};
}

}  // namespace asperity::cli
