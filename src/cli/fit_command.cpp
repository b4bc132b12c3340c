// asperity fit FIT.yaml [--out DIR] [--threads N] [--no-profile] [--no-error-bars] [--quiet]
//                       [--task I/N|auto | --collect]
// Every evaluation is journaled as it finishes (fit/fit_journal.hpp); rerunning into the same
// folder replays them. --task runs one array task's share of a separate fit into
// DIR/tasks/I-of-N/; --collect writes the results folder from the tasks' journals.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>

#include "cli/commands.hpp"
#include "cli/interrupt.hpp"
#include "cli/options.hpp"
#include "fit/fit.hpp"
#include "fit/fit_inputs.hpp"
#include "fit/fit_journal.hpp"
#include "fit/fit_load.hpp"
#include "fit/fit_tasks.hpp"
#include "io/atomic_file.hpp"
#include "io/dir_lock.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/progress.hpp"
#include "io/provenance.hpp"
#include "io/safe_open.hpp"
#include "observe/run_monitor.hpp"
#include "report/fit_writer.hpp"
#include "report/output_dir.hpp"

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
  std::string task;  // "I/N" or "auto": one array task of a separate fit
  bool collect = false;
  FigureFormats figures;  // of the fit's figures (--figures)
};

namespace fs = std::filesystem;

// The journal folder of one writer: DIR itself, or DIR/tasks/I-of-N for an array task.
fs::path task_dir(const fs::path& out, const io::Shard& t) {
  return out / "tasks" / (std::to_string(t.index) + "-of-" + std::to_string(t.count));
}

// --collect: the tasks' journals (read-only), each checked against its task's inputs; every task
// I of one N must be there, none running.
std::vector<std::unique_ptr<io::DirLock>> open_task_journals(FitJournal& journal, const fs::path& out,
                                                             const FitSpec& spec,
                                                             const std::vector<std::string>& overrides,
                                                             const std::string& build) {
  const fs::path tasks = out / "tasks";
  std::uint64_t count = 0;
  std::vector<std::uint64_t> seen;
  std::error_code ec;
  if (fs::is_directory(tasks, ec))
    for (const auto& e : fs::directory_iterator(tasks)) {
      const std::string n = e.path().filename().string();
      if (n.rfind(".", 0) == 0) continue;  // temporaries
      io::Shard t;
      try {
        const std::size_t of = n.find("-of-");
        if (of == std::string::npos) throw std::invalid_argument(n);
        t = io::parse_shard(n.substr(0, of) + "/" + n.substr(of + 4), {}, "--collect");
      } catch (const std::invalid_argument&) {
        throw io::InputError(e.path().string(), 0, "--collect", "not a task folder (expected I-of-N)");
      }
      if (count != 0 && t.count != count)
        throw io::InputError(e.path().string(), 0, "--collect",
                             "tasks of two splits (" + std::to_string(count) + " and " + std::to_string(t.count) +
                                 " tasks); remove the stale ones");
      count = t.count;
      seen.push_back(t.index);
    }
  if (count == 0)
    throw io::InputError(tasks.string(), 0, "--collect",
                         "no array task has run into " + out.string() + " (asperity fit FIT --task I/N)");
  std::vector<std::unique_ptr<io::DirLock>> locks;
  for (std::uint64_t i = 0; i < count; ++i) {
    const io::Shard t{i, count};
    const fs::path d = task_dir(out, t);
    if (std::find(seen.begin(), seen.end(), i) == seen.end() || !fs::exists(d / "journal.csv"))
      throw io::InputError(
          d.string(), 0, "--collect",
          "task " + std::to_string(i) + "/" + std::to_string(count) + " has not run (no journal); run it first");
    locks.push_back(lock_fit_journal_dir(d, "--out"));  // a task still writing is refused here
    check_fit_inputs(d / "inputs.txt", fit_inputs_text(spec, overrides, build, t));
    journal.open(d / "journal.csv", false);
  }
  return locks;
}

// --task I/N|auto (0/1 without it).
io::Shard parse_task(const FitCliOptions& opt) {
  if (opt.task.empty()) return {};
  try {
    return io::parse_shard(
        opt.task, [](const char* n) { return std::getenv(n); }, "--task");
  } catch (const std::invalid_argument& e) {
    throw io::InputError("", 0, "--task", e.what());
  }
}

// The locks a fit holds while it runs: its journal folder's, and with --collect every task's.
struct JournalLocks {
  std::unique_ptr<io::DirLock> own;
  std::vector<std::unique_ptr<io::DirLock>> tasks;
};

// Opens the journal this run appends to (OUT/ or its task's folder), or with --collect every
// task's journal for replay.
JournalLocks open_journals(FitJournal& journal, const FitCliOptions& opt, const fs::path& out, const FitSpec& spec,
                           const io::Shard& task) {
  const std::string build = io::code_build_id();
  JournalLocks locks;
  if (opt.collect) {
    locks.own = lock_fit_journal_dir(out, "--out");
    locks.tasks = open_task_journals(journal, out, spec, opt.overrides, build);
    return locks;
  }
  const fs::path dir = opt.task.empty() ? out : task_dir(out, task);
  // tasks/ and tasks/I-of-N/ must be real folders inside --out: a link there would put the
  // journal elsewhere.
  io::check_real_folders(out, dir.lexically_relative(out), "--out");
  fs::create_directories(dir);
  locks.own = lock_fit_journal_dir(dir, "--out");
  io::remove_stale_temporaries(dir);  // of a fit that died while writing (kill -9, a lost node)
  open_fit_journal(journal, dir, fit_inputs_text(spec, opt.overrides, build, task));
  return locks;
}

// The progress line of a fit: every evaluation it makes (optimizations, best re-runs, profiles,
// Hessians, error-bar refits) against their budget, which a finished optimization gives back
// what it left unused (until then the ETA is an upper bound); the finished fits; and, for one
// optimization, its best objective so far (of several, each has its own: their lines say it).
class EvaluationProgress {
 public:
  EvaluationProgress(double budget, std::size_t fits, bool quiet)
      : line_("fit", "evaluations (at most)", budget, quiet), fits_(fits) {}
  void tick(const FitTick& t) {  // thread-safe
    std::string extra;
    double done;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done_ += t.counted();
      if (t.done())
        ++finished_;
      else if (std::string_view(t.part) == "fit" && t.objective < best_)
        best_ = t.objective;
      done = done_;
      if (fits_ > 1)
        extra = std::to_string(finished_) + " of " + std::to_string(fits_) + " fits done";
      else if (best_ < HUGE_VAL)
        extra = "best J so far " + io::format_printf("%.4g", best_);
    }
    line_.update(done, extra);
  }
  void close() { line_.close(); }

 private:
  io::ProgressLine line_;
  std::size_t fits_;
  std::mutex mutex_;
  double done_ = 0;
  std::size_t finished_ = 0;
  double best_ = HUGE_VAL;
};

// The summary lines and the exit code of a finished fit: a failed optimization, or one whose
// best objective no second start confirmed (converged no or unverified, as a drifted regression),
// is a failed check, one line each on stderr; with optimizer.certify false an unconfirmed
// optimum is said, not failed.
int report_fit(const FitCliOptions& opt, const FitSpec& spec, const FitResult& result, const fs::path& written) {
  int evaluations = 0, certified = 0;
  bool ok = true;
  for (const auto& o : result.fits) {
    evaluations += o.evaluations;
    ok = ok && o.ok() && (!spec.certify || o.converged == Converged::yes);
    certified += o.certified() ? 1 : 0;
  }
  if (!opt.quiet) {
    std::printf(
        "  %d evaluations in %zu fit(s); optimizations %.3f s (sum), total wall %.3f s (incl. profile, error-bar "
        "refits)\n",
        evaluations, result.fits.size(), result.fit_wall_s, result.wall_s);
    std::printf("  converged: %d of %zu certified (>= 2 starts in the best basin)\n  -> %s\n", certified,
                result.fits.size(), written.string().c_str());
  }
  for (const auto& o : result.fits) {
    if (!o.ok())
      std::cerr << "fit " << o.label << " failed: " << o.failure << '\n';
    else if (o.converged == Converged::yes)
      continue;
    else if (spec.certify)
      std::cerr << "fit " << o.label << (o.converged == Converged::no ? " did not converge: " : " is not certified: ")
                << o.convergence
                << (o.converged == Converged::unverified ? ", or optimizer.certify: false to accept it unconfirmed"
                                                         : "")
                << '\n';
    else if (!opt.quiet)
      std::cerr << "fit " << o.label << " not certified (optimizer.certify: false): " << o.convergence << '\n';
  }
  return ok ? exit_ok : exit_failure;
}

int run(const FitCliOptions& opt, const Invocation& inv) {
  const FitSpec spec = load_fit(opt.fit_file, opt.overrides);
  const std::filesystem::path out =
      opt.out.empty() ? std::filesystem::path("results") / "fits" / spec.name : std::filesystem::path(opt.out);
  const bool sharded = !opt.task.empty();
  const io::Shard task = parse_task(opt);
  if ((sharded || opt.collect) && !spec.separate)
    throw io::InputError(
        opt.fit_file, 0, sharded ? "--task" : "--collect",
        "a joint fit (separate: false) is one optimization and cannot be split into array tasks; run it without " +
            std::string(sharded ? "--task" : "--collect"));
  // The folder is claimed (made, with the marker) before the fit, so its journal can live there;
  // only a folder asperity fit made, or a new or empty one, is used.
  claim_fit_dir(out);
  FitJournal journal;
  const JournalLocks locks = open_journals(journal, opt, out, spec, task);
  FitOptions fo;
  fo.journal = &journal;
  fo.replay_only = opt.collect;
  if (sharded) {
    fo.only = task_optimizations(spec, task);
    if (fo.only.empty()) {  // more tasks than experiments: this one's (empty) journal says it ran
      if (!opt.quiet)
        std::printf("task %s: no experiment falls to this task (%zu experiments)\n", opt.task.c_str(),
                    spec.experiments.size());
      return exit_ok;
    }
  }
  fo.threads = threads_or_all(opt.threads);
  fo.profile = !opt.no_profile;
  fo.error_bars = !opt.no_error_bars;
  if (!opt.quiet) {
    std::printf("%s: %s, %zu experiment(s)%s, %s, %d thread(s)\n", opt.fit_file.c_str(), objective_name(spec.objective),
                spec.experiments.size(), spec.separate ? " fitted separately" : " fitted jointly",
                spec.algorithm.c_str(), threads_or_all(opt.threads));
    std::fflush(stdout);
    fo.progress = [](const std::string& line) {
      io::print_line(stdout, "  " + line);
    };  // never glued onto the progress line
  }
  const std::size_t optimizations = sharded ? fo.only.size() : spec.separate ? spec.experiments.size() : 1;
  EvaluationProgress progress(static_cast<double>(fit_run_budget(spec, fo)), optimizations, opt.quiet);
  fo.on_evaluation = [&](const FitTick& t) { progress.tick(t); };
  FitResult result;
  try {
    const InterruptRequest ctrl_c;  // Ctrl-C: the evaluations in flight stop, the journal keeps the rest
    fo.stop = ctrl_c.flag();
    result = run_fit(spec, fo);
  } catch (const RunInterrupted&) {
    const std::filesystem::path journal_file = (sharded ? task_dir(out, task) : out) / "journal.csv";
    io::print_line(stderr, "fit: interrupted; " + std::to_string(journal.size()) + " evaluation(s) kept in " +
                               journal_file.string() + "; rerun the same command to resume");
    return exit_interrupted;
  } catch (const NotJournaled& e) {
    throw io::InputError((out / "tasks").string(), 0, "--collect",
                         std::string(e.what()) +
                             ": a task has not finished (run it again: it resumes) or ran with other "
                             "--no-profile/--no-error-bars/--set options than this collect");
  }
  progress.close();  // what follows starts on a line of its own
  if (!opt.quiet) {
    std::printf("  evaluations: %d replayed from the journal, %d computed\n", result.replayed, result.computed);
    std::fflush(stdout);
  }
  if (!sharded) write_fit(out, spec, result, inv.command_line, opt.figures);
  return report_fit(opt, spec, result, sharded ? task_dir(out, task) / "journal.csv" : out);
}

}  // namespace

Command add_fit_command(CLI::App& app) {
  auto opt = std::make_shared<FitCliOptions>();
  CLI::App* sub = app.add_subcommand("fit",
                                     "Calibrate model parameters against measurements with NLopt "
                                     "(writes results/fits/<name>/). Every evaluation is journaled as it "
                                     "finishes (DIR/journal.csv): rerun the same command to resume a killed fit");
  sub->add_option("fit", opt->fit_file, "Fit YAML file (see fits/)")->required();
  sub->add_option("--out,-o", opt->out,
                  "Results directory (default: results/fits/<name>/); one this fit made is resumed");
  add_threads_option(sub, opt->threads, "Worker threads (experiments or per-experiment fits in parallel)");
  add_set_option(sub, opt->overrides,
                 "in every experiment's scene (the fit's parameters and the objective's own settings win)");
  sub->add_flag("--no-profile", opt->no_profile, "Skip the objective profile around the optimum");
  sub->add_flag("--no-error-bars", opt->no_error_bars, "Skip the error-bar refits");
  add_quiet_flag(sub, opt->quiet);
  add_figures_option(sub, opt->figures);
  auto* task = sub->add_option("--task", opt->task,
                               "Run only array task I of N of a separate fit (I/N, or auto: the SLURM array task), "
                               "journaled into DIR/tasks/I-of-N/; then --collect");
  sub->add_flag("--collect", opt->collect,
                "Write the results folder from the journals of all --task runs (no optimization is re-run; "
                "each experiment's best run is, for its curves)")
      ->excludes(task);
  return Command{sub, [opt](const Invocation& inv) { return run(*opt, inv); }};
}

}  // namespace asperity::cli
