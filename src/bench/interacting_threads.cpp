#include "bench/interacting_threads.hpp"

#include <omp.h>

#include <chrono>
#include <cstdio>
#include <sstream>

#include "bench/busy_core.hpp"
#include "bench/interacting.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "observe/recorder.hpp"
#include "observe/simulate.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"
#include "solve/interacting/interacting_event_stepper.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

ThreadsBenchRow timed(const Scene& scene, int threads, const char* load) {
  omp_set_num_threads(threads);  // the solver's teams take their width at construction
  ThreadsBenchRow row;
  row.load = load;
  row.N = scene.experiment.junctions.size();
  row.threads = threads;
  const Problem problem = make_problem(scene);
  Recorder rec = make_recorder(scene);
  const auto t0 = std::chrono::steady_clock::now();
  InteractingEventStepper stepper(problem);
  const RunInfo info = integrate(stepper, problem, rec);
  row.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto w = stepper.junctions().work();
  row.pass_s = w.pass_s, row.fold_s = w.fold_s, row.rebuild_s = w.rebuild_s, row.remove_s = w.remove_s;
  row.law_s = w.law_s, row.update_s = w.update_s;
  row.slips = info.stats.slips;
  row.iterations = w.iterations;
  const FirstPeak fp = rec.first_peak();
  row.Q_s = fp.max.Q, row.A_s = fp.max.A, row.t_peak = fp.max.t;
  return row;
}

}  // namespace

std::vector<ThreadsBenchRow> run_threads_bench(const ThreadsBenchOptions& opt) {
  const Scene base = load_scene(opt.scene);
  const int restore = omp_get_max_threads();
  int widest = 1;
  for (int t : opt.threads) widest = std::max(widest, t);
  std::vector<ThreadsBenchRow> rows;
  for (std::size_t N : opt.sizes) {
    Scene s = bench_population(base, N);
    s.output.series.clear();
    s = with_positions(s, population_radius(base, N, opt.contact_radius_m));
    timed(s, widest, "warm-up");  // tables, pages, caches: not in the first timed row
    for (int t : opt.threads) {
      rows.push_back(timed(s, t, "quiet"));
      if (opt.log)
        *opt.log << "  N " << N << ", quiet, " << t << " thread(s): " << rows.back().wall_s << " s" << std::endl;
    }
    if (opt.busy) {
      // One core held by another process for the two runs (bounded: it dies with this process,
      // or after an hour).
      const BusyCore busy(3600);
      for (int t : {1, widest}) {
        rows.push_back(timed(s, t, "busy"));
        if (opt.log)
          *opt.log << "  N " << N << ", one core busy, " << t << " thread(s): " << rows.back().wall_s << " s"
                   << std::endl;
      }
    }
  }
  omp_set_num_threads(restore);
  return rows;
}

void write_threads_bench(const fs::path& dir, const std::vector<ThreadsBenchRow>& rows) {
  std::ostringstream o;
  o << "load,N,threads,wall_s,pass_s,fold_s,rebuild_s,remove_s,law_s,update_s,rest_s,slips,chord_iterations,Q_s_N,A_s_"
       "m2,"
       "t_peak_s\n";
  for (const auto& r : rows)
    o << r.load << ',' << r.N << ',' << r.threads << ',' << io::csv_number(r.wall_s) << ',' << io::csv_number(r.pass_s)
      << ',' << io::csv_number(r.fold_s) << ',' << io::csv_number(r.rebuild_s) << ',' << io::csv_number(r.remove_s)
      << ',' << io::csv_number(r.law_s) << ',' << io::csv_number(r.update_s) << ',' << io::csv_number(r.rest_s()) << ','
      << r.slips << ',' << r.iterations << ',' << io::csv_number(r.Q_s) << ',' << io::csv_number(r.A_s) << ','
      << io::csv_number(r.t_peak) << '\n';
  fs::create_directories(dir);
  io::write_text_file(dir / "interacting_threads.csv", o.str());
}

std::string threads_bench_table(const std::vector<ThreadsBenchRow>& rows) {
  std::ostringstream o;
  char line[400];
  std::snprintf(
      line, sizeof line,
      "  %-5s %5s %3s %8s %6s | seconds by phase: %7s %7s %7s %7s %7s %7s %7s | efficiency t1/(p tp): %5s %5s "
      "%5s %5s %5s %5s %5s\n",
      "load", "N", "thr", "wall s", "x 1thr", "pass", "fold", "rebuild", "remove", "law", "update", "rest", "pass",
      "fold", "rebld", "remov", "law", "updat", "rest");
  o << line;
  for (const auto& r : rows) {
    const ThreadsBenchRow* one = nullptr;        // the same load's one-thread row
    const ThreadsBenchRow* quiet_one = nullptr;  // the quiet one-thread row
    for (const auto& q : rows) {
      if (q.N != r.N || q.threads != 1) continue;
      if (q.load == r.load) one = &q;
      if (q.load == "quiet") quiet_one = &q;
    }
    const double p = r.threads;
    const auto eff = [&](double t1, double tp) { return tp > 0 ? t1 / (p * tp) : 0.0; };
    const ThreadsBenchRow& b = quiet_one ? *quiet_one : r;
    std::snprintf(
        line, sizeof line,
        "  %-5s %5zu %3d %8.4g %6.3g | %17s %7.3g %7.3g %7.3g %7.3g %7.3g %7.3g %7.3g | %21s %5.2f %5.2f %5.2f %5.2f "
        "%5.2f %5.2f %5.2f\n",
        r.load.c_str(), r.N, r.threads, r.wall_s, one ? r.wall_s / one->wall_s : 0.0, "", r.pass_s, r.fold_s,
        r.rebuild_s, r.remove_s, r.law_s, r.update_s, r.rest_s(), "", eff(b.pass_s, r.pass_s), eff(b.fold_s, r.fold_s),
        eff(b.rebuild_s, r.rebuild_s), eff(b.remove_s, r.remove_s), eff(b.law_s, r.law_s), eff(b.update_s, r.update_s),
        eff(b.rest_s(), r.rest_s()));
    o << line;
  }
  return o.str();
}

}  // namespace asperity
