// asperity bench tradeoff|accuracy|savings [--out results/bench] [--quick] ...
// Benchmarks that print measured figures and write them under results/bench/ (issue 3).
#include <omp.h>

#include <cstdio>
#include <fstream>
#include <thread>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "bench/accuracy.hpp"
#include "bench/bench_scene.hpp"
#include "bench/savings.hpp"
#include "bench/tradeoff.hpp"
#include "cli/commands.hpp"

namespace asperity::cli {
namespace {

struct BenchOptions {
  std::string out = "results/bench";
  bool quick = false;
  int repeats = 5;
  int threads = 1;
  // tradeoff
  std::string scene = "bench/scenes/P0.20N.yaml";
  std::string ratio_scene = "scenes/paper/P4.00N.yaml";
  std::vector<double> Ct;
  double window = 2e-3;
  // accuracy, savings
  std::string scenes_dir = "scenes/paper";
  std::vector<std::string> scenes;
  std::vector<double> tolerances;
};

// The machine's load when the figures were taken: timings on a shared machine depend on it.
std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string one;
  return in >> one ? one : "unknown";
}

void machine_line(const BenchOptions& b) {
  omp_set_num_threads(b.threads);
  std::printf("(%d OpenMP thread(s) for the reference, %u hardware threads, load average %s; "
              "wall-clock timings on this machine)\n",
              omp_get_max_threads(), std::thread::hardware_concurrency(), load_average().c_str());
}

int tradeoff(const BenchOptions& b) {
  TradeoffOptions o;
  o.scene = b.scene;
  o.ratio_scene = b.ratio_scene;
  o.repeats = b.repeats;
  o.ref_window_s = b.window;
  o.log = &std::cout;
  if (!b.Ct.empty()) o.Ct = b.Ct;
  if (b.quick) {
    if (b.Ct.empty()) o.Ct = {1e2, 1e3};
    o.tolerances = {1e-4, 1e-6, 1e-8, 1e-10};
    o.repeats = 1;
    o.ref_window_s = std::min(o.ref_window_s, 5e-4);
  }
  machine_line(b);
  const TradeoffResult r = run_tradeoff(o);
  write_tradeoff(b.out, r);
  std::printf("reference order of convergence (log error ratio / log C_t ratio):\n");
  for (const auto& x : r.orders)
    std::printf("  %-9s C_t %g -> %g: %.3g\n", x.observable.c_str(), x.Ct_lo, x.Ct_hi, x.order);
  const SpeedRatio& s = r.speed;
  std::printf("speed on %s (stand-in): reference (C_t = %g, %d threads) %.4g s wall for a %.4g s window "
              "= %.4g s per simulated second; event (tolerance %g) %.4g s wall through peak + %d cycles "
              "(%.4g s simulated) = %.4g s per simulated second; ratio %.3g\n",
              s.experiment.c_str(), s.ref_Ct, s.threads, s.ref_wall_s, s.ref_window_s, s.ref_wall_per_sim(),
              s.ev_tolerance, s.ev_wall_s, s.ev_cycles, s.ev_t_end, s.ev_wall_per_sim(), s.ratio());
  std::printf("-> %s/{work_precision.csv,work_precision.png,reference_order.csv,speed_ratio.csv}\n", b.out.c_str());
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
  const auto rows = run_accuracy(o);
  write_accuracy(b.out, rows);
  int ok = 0;
  for (const auto& r : rows) ok += r.within_targets();
  std::printf("%d of %zu runs within the targets (1e-4 loading branch, 1e-2 stick-slip) -> %s/accuracy.csv\n",
              ok, rows.size(), b.out.c_str());
  return exit_ok;
}

int savings(const BenchOptions& b) {
  SavingsOptions o;
  if (!b.scenes.empty()) o.scenes = {b.scenes.begin(), b.scenes.end()};
  o.repeats = b.quick ? 1 : b.repeats;
  o.scratch = std::filesystem::path(b.out) / ".savings-scratch";
  o.log = &std::cout;
  machine_line(b);
  const auto rows = run_savings(o);
  write_savings(b.out, rows);
  auto cpu_ms = [](const SavingRow& r) { return (r.cpu_s + r.write_s) * 1e3; };
  for (std::size_t i = 0; i + 1 < rows.size(); i += 2)
    std::printf("  %s %s: %s %.4g ms CPU -> %s %.4g ms CPU (x%.3g; wall %.4g -> %.4g ms)\n",
                rows[i].experiment.c_str(), rows[i].saving.c_str(), rows[i].variant.c_str(), cpu_ms(rows[i]),
                rows[i + 1].variant.c_str(), cpu_ms(rows[i + 1]), cpu_ms(rows[i]) / cpu_ms(rows[i + 1]),
                rows[i].total_s() * 1e3, rows[i + 1].total_s() * 1e3);
  std::printf("-> %s/{savings.csv,savings.png}\n", b.out.c_str());
  return exit_ok;
}

}  // namespace

Command add_bench_command(CLI::App& app) {
  auto opt = std::make_shared<BenchOptions>();
  CLI::App* sub = app.add_subcommand("bench", "Benchmarks: speed-accuracy trade, accuracy on the stand-ins, savings");
  sub->require_subcommand(1);
  sub->fallthrough();  // --out, --quick, --repeats also after the sub-subcommand
  sub->add_option("--out,-o", opt->out, "Output folder")->capture_default_str();
  sub->add_flag("--quick", opt->quick, "Fewer settings and repeats (a smoke run, not the published figures)");
  sub->add_option("--repeats", opt->repeats, "Runs faster than 1 s: median wall time of this many")
      ->capture_default_str()
      ->check(CLI::Range(1, 100));
  sub->add_option("--threads", opt->threads,
                  "OpenMP threads of the reference solver (the event solver uses one below 65536 "
                  "never-slipped junctions; on a shared 2-core machine 2 threads made the reference slower)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));

  CLI::App* t = sub->add_subcommand("tradeoff", "Work-precision study (reference C_t vs event tolerance) and "
                                                "the reference/event speed ratio on P4.00N");
  t->add_option("--scene", opt->scene, "Work-precision experiment (the reference must finish it)")
      ->capture_default_str();
  t->add_option("--ratio-scene", opt->ratio_scene, "Scene of the speed ratio")->capture_default_str();
  t->add_option("--ct", opt->Ct, "Reference C_t values (default 1e2 1e3 1e4)")->check(CLI::PositiveNumber);
  t->add_option("--window", opt->window, "Simulated window of the timed reference on the ratio scene [s]")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  CLI::App* a = sub->add_subcommand("accuracy", "Default tolerance vs converged (1e-12) on the paper scenes, "
                                                "through peak + 5 stick-slip cycles");
  a->add_option("--scenes-dir", opt->scenes_dir, "Folder of the scenes")->capture_default_str();
  a->add_option("--scene", opt->scenes, "Scene(s) instead of the folder");
  a->add_option("--tolerance", opt->tolerances, "Tolerance(s) to test (default: each scene's own)")
      ->check(CLI::PositiveNumber);
  CLI::App* s = sub->add_subcommand("savings", "Wall time saved by series=[], stop.at_first_peak, alpha_b=0");
  s->add_option("--scene", opt->scenes, "Scene(s) (default scenes/paper/P4.00N.yaml)");

  return Command{sub, [opt, t, a, s] {
    if (t->parsed()) return tradeoff(*opt);
    if (a->parsed()) return accuracy(*opt);
    if (s->parsed()) return savings(*opt);
    return exit_input;
  }};
}

}  // namespace asperity::cli
