// asperity bench tradeoff|speed|accuracy|savings [--out results/bench] [--quick] ...
// Benchmarks that print measured figures and write them under results/bench/.
#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench/accuracy.hpp"
#include "bench/bench_scene.hpp"
#include "bench/contact.hpp"
#include "bench/interacting.hpp"
#include "bench/interacting_threads.hpp"
#include "bench/savings.hpp"
#include "bench/speed_ratio.hpp"
#include "bench/tradeoff.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "io/progress.hpp"
#include "report/gnuplot.hpp"
#include "report/output_dir.hpp"
#include "solve/interacting/kernel_form.hpp"

namespace asperity::cli {
namespace {

struct BenchOptions {
  std::string out = "results/bench";
  bool quick = false;
  int repeats = 5;
  int threads = 1;
  bool quiet = false;
  FigureFormats figures;  // of work_precision and savings (--figures)
  bool redraw = false;    // tradeoff, savings: the figure again from the CSV in --out, nothing measured
  // tradeoff
  std::string scene = "bench/scenes/P0.20N.yaml";
  std::vector<double> Ct;
  // speed
  std::string speed_scene = "scenes/paper/P4.00N.yaml";
  std::vector<double> whole_Ct;
  double window = 2e-3;
  // accuracy, savings
  std::string scenes_dir = "scenes/paper";
  std::vector<std::string> scenes;
  std::vector<double> tolerances;
  // interacting
  std::vector<std::size_t> interacting_sizes;
  std::vector<int> threads_scan;  // --threads-scan: the per-phase thread table instead
  bool busy = false;              // --busy: also with one core held by another process
  // contact
  std::vector<std::size_t> contact_sizes;
};

// The machine's load when the figures were taken: timings on a shared machine depend on it.
std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  return in >> one ? one : "unknown";
}

// The files the benchmarks write: a folder holding only these (before markers existed) is ours.
bool bench_folder(const std::filesystem::path& d) {
  static const char* const ours[] = {"accuracy.csv",    "reference_order.csv",     "savings.csv",
                                     "savings.png",     "speed_ratio.csv",         "speed_runs.csv",
                                     "interacting.csv", "interacting_threads.csv", "interacting_tradeoff.csv",
                                     "contact.csv",     "work_precision.csv",      "work_precision.png"};
  bool any = false;
  for (const auto& e : std::filesystem::directory_iterator(d)) {
    const std::string n = e.path().filename().string();
    if (n.rfind(".savings-scratch", 0) == 0) continue;
    if (std::find(std::begin(ours), std::end(ours), n) == std::end(ours)) return false;
    any = true;
  }
  return any;
}

// Before minutes of benchmarking: refuse an --out that is not ours (the folder is made, and
// marked, only when the results are written).
void check_out(const BenchOptions& b) { check_ours(b.out, "bench", "--out", bench_folder); }

void machine_line(const BenchOptions& b) {
  check_out(b);
  omp_set_num_threads(b.threads);
  std::printf(
      "(%d OpenMP thread(s) for the reference, %u hardware threads, load average %s; "
      "wall-clock timings on this machine)\n",
      omp_get_max_threads(), std::thread::hardware_concurrency(), load_average().c_str());
}

// --redraw: `figure` (and its .gp) drawn again from the CSV the bench wrote in --out by `draw`;
// nothing is measured and nothing else written. Exit 1 when gnuplot did not draw it.
int redraw(const BenchOptions& b, const std::string& figure, const std::function<bool(std::string*)>& draw) {
  std::string why;
  const std::filesystem::path png = std::filesystem::path(b.out) / figure;
  if (!draw(&why)) {
    std::fprintf(stderr, "%s: not drawn: %s\n", png.string().c_str(), why.c_str());
    return exit_failure;
  }
  std::string drawn;
  for (const auto& f : figure_files(png, b.figures)) drawn += (drawn.empty() ? "" : ", ") + f.string();
  std::printf("-> %s (and %s), redrawn from the CSV\n", drawn.c_str(), plot_script_path(png).string().c_str());
  return exit_ok;
}

int tradeoff(const BenchOptions& b) {
  if (b.redraw)
    return redraw(b, "work_precision.png",
                  [&](std::string* why) { return redraw_tradeoff(b.out, b.scene, b.figures, why); });
  TradeoffOptions o;
  o.scene = b.scene;
  o.repeats = b.repeats;
  o.log = &std::cout;
  if (!b.Ct.empty()) o.Ct = b.Ct;
  if (b.quick) {
    if (b.Ct.empty()) o.Ct = {1e2, 1e3};
    o.tolerances = {1e-4, 1e-6, 1e-8, 1e-10};
    o.repeats = 1;
  }
  machine_line(b);
  io::ProgressLine progress("bench tradeoff", "settings", 0, b.quiet);
  o.on_setting = [&](std::size_t done, std::size_t total) {
    progress.set_total(static_cast<double>(total));
    progress.update(static_cast<double>(done));
  };
  const TradeoffResult r = run_tradeoff(o);
  write_tradeoff(b.out, r, b.figures);
  // The interacting solver's knobs (tolerances, cut-off) on a stand-in with junction positions.
  InteractingTradeoffOptions io;
  io.repeats = o.repeats;
  io.log = &std::cout;
  if (b.quick) io.tolerances = {1e-6, 1e-9}, io.interaction_tolerances = {1e-4, 1e-6}, io.cutoffs_m = {5e-4, 2e-3};
  std::printf("interacting event solver on %s (STAND-IN), errors vs the full kernel at both tolerances %g:\n",
              io.scene.string().c_str(), io.converged_tolerance);
  write_interacting_tradeoff(b.out, run_interacting_tradeoff(io));
  write_marker(b.out, "bench");
  std::printf("reference order of convergence (log error ratio / log C_t ratio):\n");
  for (const auto& x : r.orders)
    std::printf("  %-9s C_t %g -> %g: %.3g\n", x.observable.c_str(), x.Ct_lo, x.Ct_hi, x.order);
  std::printf("-> %s/{work_precision.csv,work_precision.png,reference_order.csv,interacting_tradeoff.csv}\n",
              b.out.c_str());
  return exit_ok;
}

int speed(const BenchOptions& b) {
  SpeedOptions o;
  o.scene = b.speed_scene;
  o.repeats = b.quick ? 1 : b.repeats;
  o.window_s = b.window;
  o.log = &std::cout;
  if (!b.whole_Ct.empty()) o.whole_run_Ct = b.whole_Ct;
  if (b.quick) {
    o.event_tolerances = {1e-4, 1e-6};
    if (b.whole_Ct.empty()) o.whole_run_Ct = {10, 20};
  }
  machine_line(b);
  const SpeedResult r = run_speed(o);
  write_speed(b.out, r);
  write_marker(b.out, "bench");
  std::printf("%s (stand-in), whole run = first peak + %d stick-slip cycles (%.4g s simulated):\n",
              r.experiment.c_str(), o.cycles, r.T_run);
  for (const auto& c : r.comparisons)
    std::printf("  %s [%s]: reference %.4g s, event %.4g s wall -> ratio %.3g wall, %.3g CPU\n", c.comparison.c_str(),
                c.basis.c_str(), c.reference.wall_s, c.event.wall_s, c.ratio_wall(), c.ratio_cpu());
  std::printf("-> %s/{speed_ratio.csv,speed_runs.csv}\n", b.out.c_str());
  return exit_ok;
}

std::vector<std::filesystem::path> scene_list(const BenchOptions& b) {
  if (!b.scenes.empty()) return {b.scenes.begin(), b.scenes.end()};
  return paper_scenes(b.scenes_dir);
}

int accuracy(const BenchOptions& b) {
  machine_line(b);
  AccuracyOptions o;
  o.scenes = scene_list(b);
  if (b.quick && b.scenes.empty()) o.scenes.resize(std::min<std::size_t>(2, o.scenes.size()));
  o.tolerances = b.tolerances;
  o.log = &std::cout;
  io::ProgressLine progress("bench accuracy", "runs", 0, b.quiet);
  o.on_run = [&](std::size_t done, std::size_t total) {
    progress.set_total(static_cast<double>(total));
    progress.update(static_cast<double>(done));
  };
  const auto rows = run_accuracy(o);
  write_accuracy(b.out, rows);
  write_marker(b.out, "bench");
  int ok = 0;
  for (const auto& r : rows) ok += r.within_targets();
  std::printf("%d of %zu runs within the targets (1e-4 loading branch, 1e-2 stick-slip) -> %s/accuracy.csv\n", ok,
              rows.size(), b.out.c_str());
  return exit_ok;
}

// --threads-scan / --busy: each size at each thread count, by phase, quiet and with one core
// held by another process.
int interacting_threads(const BenchOptions& b) {
  ThreadsBenchOptions o;
  if (!b.interacting_sizes.empty()) o.sizes = b.interacting_sizes;
  if (!b.threads_scan.empty())
    o.threads = b.threads_scan;
  else
    o.threads = {1, std::max(2, static_cast<int>(std::thread::hardware_concurrency()))};
  if (o.threads.front() != 1) o.threads.insert(o.threads.begin(), 1);  // efficiencies need one thread
  o.busy = b.busy;
  o.log = &std::cout;
  machine_line(b);
  std::printf("interacting event solver by thread count%s (STAND-IN P4.00N areas; kernels %s)\n",
              b.busy ? ", quiet and with one core busy" : "", kernel_form_name(kernel_form()));
  const auto rows = run_threads_bench(o);
  write_threads_bench(b.out, rows);
  write_marker(b.out, "bench");
  std::printf("%s", threads_bench_table(rows).c_str());
  std::printf("-> %s/interacting_threads.csv\n", b.out.c_str());
  return exit_ok;
}

int interacting(const BenchOptions& b) {
  if (b.busy || !b.threads_scan.empty()) return interacting_threads(b);
  InteractingBenchOptions o;
  if (!b.interacting_sizes.empty()) o.sizes = b.interacting_sizes;
  if (b.quick) o.sizes = {300, 600}, o.whole_run = false;
  o.log = &std::cout;
  machine_line(b);
  std::printf("interacting event solver (STAND-IN P4.00N areas; OpenMP threads: %d)\n", omp_get_max_threads());
  const auto rows = run_interacting_bench(o);
  write_interacting_bench(b.out, rows);
  write_marker(b.out, "bench");
  std::printf("  %s\n", fitted_exponent_text(rows).c_str());
  std::printf("-> %s/interacting.csv\n", b.out.c_str());
  return exit_ok;
}

int contact(const BenchOptions& b) {
  ContactBenchOptions o;
  if (!b.contact_sizes.empty()) o.sizes = b.contact_sizes;
  if (b.quick) o.sizes = {128, 256};
  o.threads = b.threads;
  o.log = &std::cout;
  machine_line(b);
  std::printf(
      "normal and tangential contact, FFT boundary elements (a sphere with a self-affine surface, 4 N, Coulomb mu 0.5; "
      "%d thread(s))\n",
      b.threads);
  const auto rows = run_contact_bench(o);
  write_contact_bench(b.out, rows);
  write_marker(b.out, "bench");
  std::printf("-> %s/contact.csv\n", b.out.c_str());
  return exit_ok;
}

int savings(const BenchOptions& b) {
  SavingsOptions o;
  if (!b.scenes.empty()) o.scenes = {b.scenes.begin(), b.scenes.end()};
  if (b.redraw)
    return redraw(b, "savings.png", [&](std::string* why) { return redraw_savings(b.out, o.scenes, b.figures, why); });
  o.repeats = b.quick ? 1 : b.repeats;
  o.scratch = std::filesystem::path(b.out) / ".savings-scratch";
  o.log = &std::cout;
  machine_line(b);
  const auto rows = run_savings(o);
  write_savings(b.out, rows, b.figures);
  write_marker(b.out, "bench");
  auto cpu_ms = [](const SavingRow& r) { return (r.cpu_s + r.write_s) * 1e3; };
  for (std::size_t i = 0; i + 1 < rows.size(); i += 2)
    std::printf("  %s %s: %s %.4g ms CPU -> %s %.4g ms CPU (x%.3g; wall %.4g -> %.4g ms)\n", rows[i].experiment.c_str(),
                rows[i].saving.c_str(), rows[i].variant.c_str(), cpu_ms(rows[i]), rows[i + 1].variant.c_str(),
                cpu_ms(rows[i + 1]), cpu_ms(rows[i]) / cpu_ms(rows[i + 1]), rows[i].total_s() * 1e3,
                rows[i + 1].total_s() * 1e3);
  std::printf("-> %s/{savings.csv,savings.png}\n", b.out.c_str());
  return exit_ok;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto opt = std::make_shared<BenchOptions>();
  CLI::App* sub =
      app.add_subcommand("bench", "Benchmarks: speed-accuracy trade, speed ratio, accuracy on the stand-ins, savings");
  sub->require_subcommand(1);
  sub->fallthrough();  // --out, --quick, --repeats also after the sub-subcommand
  sub->add_option("--out,-o", opt->out, "Output folder")->capture_default_str();
  add_figures_option(sub, opt->figures);
  sub->add_flag("--quick", opt->quick, "Fewer settings and repeats (a smoke run, not the published figures)");
  sub->add_option("--repeats", opt->repeats, "Runs faster than 1 s: median wall time of this many")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  // Default 1, not all: a benchmark times one thread unless asked (on a shared machine a second
  // thread can make the reference slower).
  add_threads_option(
      sub, opt->threads,
      "OpenMP threads of the reference solver (the event solver uses one below 65536 never-slipped junctions)");
  add_quiet_flag(sub, opt->quiet);

  CLI::App* t = sub->add_subcommand("tradeoff", "Work-precision study (reference C_t vs event tolerance)");
  t->add_option("--scene", opt->scene, "Work-precision experiment (the reference must finish it)")
      ->capture_default_str();
  t->add_option("--ct", opt->Ct, "Reference C_t values (default 1e2 1e3 1e4)")->check(CLI::PositiveNumber);
  t->add_flag("--redraw", opt->redraw,
              "Measure nothing: draw work_precision.png (and .gp) again from the work_precision.csv in --out "
              "(--scene: the one it was run on, for the stand-in mark)");
  CLI::App* sp = sub->add_subcommand("speed",
                                     "Reference vs event solver over the whole run (peak + 5 cycles) of "
                                     "a paper scene, each with its error against a tight event run");
  sp->add_option("--scene", opt->speed_scene, "Scene")->capture_default_str();
  sp->add_option("--ct", opt->whole_Ct,
                 "C_t of the whole reference runs (default 25 100; the last is the "
                 "one compared and extrapolated to 1e4)")
      ->check(CLI::PositiveNumber);
  sp->add_option("--window", opt->window, "Early window of the per-step cost check at C_t 1e4 [s]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  CLI::App* a = sub->add_subcommand("accuracy",
                                    "Default tolerance vs converged (1e-12) on the paper scenes, "
                                    "through peak + 5 stick-slip cycles");
  a->add_option("--scenes-dir", opt->scenes_dir, "Folder of the scenes")->capture_default_str();
  a->add_option("--scene", opt->scenes, "Scene(s) instead of the folder");
  a->add_option("--tolerance", opt->tolerances, "Tolerance(s) to test (default: each scene's own)")
      ->check(CLI::PositiveNumber);
  CLI::App* s = sub->add_subcommand("savings", "Wall time saved by series=[], stop.at_first_peak, alpha_b=0");
  s->add_option("--scene", opt->scenes, "Scene(s) (default scenes/paper/P4.00N.yaml)");
  s->add_flag("--redraw", opt->redraw,
              "Measure nothing: draw savings.png (and .gp) again from the savings.csv in --out "
              "(--scene: those it was run on, for the stand-in mark)");
  CLI::App* in = sub->add_subcommand("interacting",
                                     "Interacting event solver: time to the first peak vs N "
                                     "(fitted exponent), peak memory vs N^2 doubles, P4.00N whole run");
  in->add_option("--sizes", opt->interacting_sizes, "Junction counts (default 300 600 1200 2400 5000)")
      ->check(CLI::Range(2, 20000));
  in->add_option("--threads-scan", opt->threads_scan,
                 "Instead: the first peak at each of these thread counts, "
                 "wall time by phase and parallel efficiency (sizes default 1200 5000)")
      ->check(CLI::Range(1, 1024));
  in->add_flag("--busy", opt->busy,
               "Instead (or with --threads-scan): also with one core kept busy by another process, "
               "at one thread and the widest count");

  CLI::App* ct = sub->add_subcommand("contact",
                                     "Rough-surface normal contact (FFT boundary elements): time and CG "
                                     "iterations vs grid size, time per iteration vs two FFT pairs, peak memory");
  ct->add_option("--sizes", opt->contact_sizes, "Pixels per side (default 256 512 1024)")->check(CLI::Range(8, 4096));

  return Command{sub, [opt, t, sp, a, s, in, ct](const Invocation&) {
                   // --quiet: the benchmarks report on stdout as they go; their results are the files.
                   if (opt->quiet && !std::freopen("/dev/null", "w", stdout)) return exit_failure;
                   if (t->parsed()) return tradeoff(*opt);
                   if (sp->parsed()) return speed(*opt);
                   if (a->parsed()) return accuracy(*opt);
                   if (s->parsed()) return savings(*opt);
                   if (in->parsed()) return interacting(*opt);
                   if (ct->parsed()) return contact(*opt);
                   return exit_input;
                 }};
}

}  // namespace asperity::cli
