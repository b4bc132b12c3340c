// asperity regress [--suite scenes/regression/suite.yaml] [--golden results/regression/golden.yaml]
//                  [--update --reason TEXT] [--threads N] [--all]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "io/provenance.hpp"
#include "regress/regress.hpp"

namespace asperity::cli {
namespace {

struct RegressOptions {
  std::string suite = "scenes/regression/suite.yaml";
  std::string golden = "results/regression/golden.yaml";
  bool update = false;
  std::string reason;
  int threads = 0;
  bool all = false;
  bool quiet = false;
};

std::string today() {
  const std::time_t t = std::time(nullptr);
  char b[32];
  std::strftime(b, sizeof b, "%Y-%m-%d", std::gmtime(&t));
  return b;
}

int regress(const RegressOptions& opt) {
  namespace fs = std::filesystem;
  if (opt.update && opt.reason.empty())
    throw io::InputError("--reason", 0, "reason", "--update needs --reason \"why the results changed\"");
  const RegressSuite suite = load_regress_suite(opt.suite);
  Golden golden;
  if (!opt.update) {
    if (!fs::exists(opt.golden))
      throw io::InputError(opt.golden, 0, "", "no golden results: bless them with --update --reason \"...\"");
    golden = load_golden(opt.golden);
  } else if (fs::exists(opt.golden)) {
    golden = load_golden(opt.golden);  // keep the history
  }
  const int threads = threads_or_all(opt.threads);
  const auto t0 = std::chrono::steady_clock::now();
  const auto results = run_regress_suite(suite, opt.update, threads);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (opt.update) {
    auto history = golden.history;
    history.push_back({today(), io::build_info().version, opt.reason});
    const Golden fresh = bless(results, history);
    fs::create_directories(fs::path(opt.golden).parent_path());
    io::write_text_file(opt.golden, golden_to_yaml(fresh));
    if (!opt.quiet)
      std::printf("blessed %zu entries in %.1f s wall (%d threads) -> %s\n", results.size(), wall, threads,
                  opt.golden.c_str());
    return exit_ok;
  }
  const auto rows = compare(golden, results);
  std::size_t bad = 0;
  for (const auto& r : rows) bad += r.ok ? 0 : 1;
  if (bad || opt.all) {
    std::printf("%-28s %-20s %24s %24s %11s %11s  %s\n", "entry", "observable", "golden", "now", "|diff|", "tolerance",
                "status");
    for (const auto& r : rows) {
      if (r.ok && !opt.all) continue;
      std::printf("%-28s %-20s %24.17g %24.17g %11.3g %11.3g  %s%s%s\n", r.entry.c_str(), r.observable.c_str(),
                  r.golden, r.now, std::abs(r.now - r.golden), r.tolerance, r.ok ? "ok" : "DRIFT",
                  r.note.empty() ? "" : ": ", r.note.c_str());
    }
  }
  if (!opt.quiet || bad)
    std::printf("regress: %zu entries, %zu values compared, %zu drifted; %.1f s wall on %d threads\n", results.size(),
                rows.size(), bad, wall, threads);
  return bad ? exit_failure : exit_ok;
}

}  // namespace

Command add_regress_command(CLI::App& app) {
  auto opt = std::make_shared<RegressOptions>();
  CLI::App* sub = app.add_subcommand("regress",
                                     "Run the regression suite and compare it with the golden results "
                                     "(exit 1 on drift)");
  sub->add_option("--suite", opt->suite, "Suite YAML (default scenes/regression/suite.yaml)");
  sub->add_option("--golden", opt->golden, "Golden results (default results/regression/golden.yaml)");
  sub->add_flag("--update", opt->update, "Re-bless: run with tightened twins, write new golden values and tolerances");
  sub->add_option("--reason", opt->reason, "Why the results changed (required with --update; kept in the history)");
  add_threads_option(sub, opt->threads, "Runs in parallel");
  add_quiet_flag(sub, opt->quiet);  // no --set: a changed scene would drift by design
  sub->add_flag("--all", opt->all, "Print every compared value, not only the drifted ones");
  return Command{sub, [opt](const Invocation&) { return regress(*opt); }};
}

}  // namespace asperity::cli
