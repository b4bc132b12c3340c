#include "bench/interacting.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bench/bench_scene.hpp"
#include "bench/robust_error.hpp"
#include "bench/timed_run.hpp"
#include "generate/positions.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "observe/recorder.hpp"
#include "observe/simulate.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

long max_rss_kB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

InteractingBenchRow timed(const std::string& what, const Scene& scene,
                          std::size_t single_from = PinnedCompliance::kSingleFrom) {
  InteractingBenchRow row;
  row.what = what;
  row.N = scene.experiment.junctions.size();
  const Problem problem = make_problem(scene);
  Recorder rec = make_recorder(scene);
  const auto t0 = std::chrono::steady_clock::now();
  InteractingEventStepper stepper(problem, single_from);
  const RunInfo info = integrate(stepper, problem, rec);
  row.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto& w = stepper.junctions().work();
  row.t_end = info.t_end;
  row.steps = info.stats.steps;
  row.slips = info.stats.slips;
  row.repins = info.stats.repins;
  row.solves = w.solves;
  row.iterations = w.iterations;
  row.rank_one = w.rank_one;
  row.rebuilds = w.rebuilds;
  row.single_passes = w.single_passes;
  row.single_refreshes = w.single_refreshes;
  const FirstPeak fp = rec.first_peak();
  row.Q_s = fp.max.Q;
  row.A_s = fp.max.A;
  row.t_peak = fp.max.t;
  row.interaction_tolerance = scene.solver.interaction_tolerance;
  row.samples = static_cast<std::int64_t>(rec.series().size());
  row.max_rss_kB = max_rss_kB();
  row.bound_kB = static_cast<double>(row.N) * static_cast<double>(row.N) * 8.0 / 1024.0;
  return row;
}

}  // namespace

Scene bench_population(const Scene& base, std::size_t N) {
  const std::vector<double>& areas = base.experiment.junctions.area_m2;
  const std::size_t N0 = areas.size();
  Scene s = base;
  s.experiment.junctions.area_m2.resize(N);
  for (std::size_t i = 0; i < N; ++i) s.experiment.junctions.area_m2[i] = areas[i % N0];
  s.experiment.mass_kg = base.experiment.mass_kg * static_cast<double>(N) / static_cast<double>(N0);
  s.stop.at_first_peak = true;
  s.stop.time = 60.0;
  s.stop.wall_time = 7200.0;
  return s;
}

double population_radius(const Scene& base, std::size_t N, double contact_radius_m) {
  return contact_radius_m * std::sqrt(static_cast<double>(N) / static_cast<double>(base.experiment.junctions.size()));
}

Scene with_positions(Scene s, double radius_m) {
  const Positions p = place_in_contact_disc(s.experiment.junctions.area_m2, radius_m, 20200318);
  s.experiment.junctions.x_m = p.x_m;
  s.experiment.junctions.y_m = p.y_m;
  s.model.interactions = Interactions::elastic;
  s.solver.method = SolverMethod::event;
  return s;
}

std::vector<InteractingBenchRow> run_interacting_bench(const InteractingBenchOptions& opt) {
  const Scene base = load_scene(opt.scene);
  std::vector<InteractingBenchRow> rows;
  bool warm = false;
  for (std::size_t N : opt.sizes) {
    Scene s = bench_population(base, N);
    const double R = population_radius(base, N, opt.contact_radius_m);
    // Side by side: the scene's own output series (what a user's run records), then none. The
    // first size is run once untimed before (tables, pages, caches), else the first timed run
    // would carry the process's warm-up.
    if (opt.recorded && !warm) {
      Scene w = s;
      w.output.series.clear();
      timed("warm-up", with_positions(w, R));
      warm = true;
    }
    if (opt.recorded) {
      rows.push_back(timed("first_peak_series", with_positions(s, R)));
    }
    s.output.series.clear();
    if (opt.converged_tolerance > 0) {
      Scene c = s;
      c.solver.interaction_tolerance = opt.converged_tolerance;
      rows.push_back(timed("first_peak_converged", with_positions(c, R)));
    }
    // From N = 2,048 on (where the solver keeps G's single-precision copy), also without it.
    const bool both = N >= PinnedCompliance::kSingleFrom;
    if (both) rows.push_back(timed("first_peak_double", with_positions(s, R), static_cast<std::size_t>(-1)));
    rows.push_back(timed("first_peak", with_positions(s, R)));
    const auto& r = rows.back();
    if (opt.log) {
      *opt.log << "  N " << r.N << ": first peak at t = " << r.t_peak << " s in " << r.wall_s << " s wall (" << r.slips
               << " slips, " << r.solves << " solves, " << r.iterations << " chord iterations, " << r.rank_one
               << " rank-one updates, " << r.rebuilds << " rebuilds), peak RSS " << r.max_rss_kB / 1024
               << " MB vs N^2 doubles " << r.bound_kB / 1024 << " MB" << std::endl;
      if (both) {
        const auto& d = rows[rows.size() - 2];
        *opt.log << "    without G's single-precision copy: " << d.wall_s << " s wall, " << d.wall_s / r.wall_s
                 << "x the time (" << r.single_passes << " of " << r.iterations << " chord passes on the copy, "
                 << r.single_refreshes << " new references); relative differences Q_s " << std::abs(r.Q_s / d.Q_s - 1)
                 << ", A_s " << std::abs(r.A_s / d.A_s - 1) << ", t_peak " << std::abs(r.t_peak / d.t_peak - 1)
                 << std::endl;
      }
      if (opt.converged_tolerance > 0) {
        const auto& c = rows[rows.size() - (both ? 3 : 2)];
        *opt.log << "    converged solves (interaction tolerance " << c.interaction_tolerance << ", against "
                 << r.interaction_tolerance << "): " << c.wall_s << " s wall, " << c.wall_s / r.wall_s
                 << "x the time; relative differences Q_s " << std::abs(r.Q_s / c.Q_s - 1) << ", A_s "
                 << std::abs(r.A_s / c.A_s - 1) << ", t_peak " << std::abs(r.t_peak / c.t_peak - 1) << std::endl;
      }
      if (opt.recorded) {
        const auto& w = rows[rows.size() - (opt.converged_tolerance > 0 ? 3 : 2) - (both ? 1 : 0)];
        *opt.log << "    with the output series (" << w.samples << " samples): " << w.wall_s << " s wall, "
                 << 100.0 * (w.wall_s / r.wall_s - 1.0) << " % more, " << w.solves - r.solves << " extra exact solves"
                 << std::endl;
      }
    }
  }
  if (opt.whole_run) {
    Scene s = base;
    s.stop.cycles = 5;
    s.stop.time = 10.0;
    s.output.series.clear();
    rows.push_back(timed("whole_run", with_positions(s, opt.contact_radius_m)));
    const auto& r = rows.back();
    if (opt.log)
      *opt.log << "  " << opt.scene.filename().string() << " (N " << r.N << "), peak + 5 cycles or stop.time: t_end "
               << r.t_end << " s in " << r.wall_s << " s wall (" << r.slips << " slips, " << r.repins
               << " repins), peak RSS " << r.max_rss_kB / 1024 << " MB" << std::endl;
  }
  return rows;
}

double fitted_exponent(const std::vector<InteractingBenchRow>& rows) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (const auto& r : rows) {
    if (r.what != "first_peak" || !(r.wall_s > 0)) continue;
    const double x = std::log(static_cast<double>(r.N)), y = std::log(r.wall_s);
    sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
  }
  const double d = n * sxx - sx * sx;  // 0 when every N is the same
  if (n < 2 || !(d > 1e-12 * n * sxx)) return NAN;
  return (n * sxy - sx * sy) / d;
}

std::string fitted_exponent_text(const std::vector<InteractingBenchRow>& rows) {
  std::size_t lo = 0, hi = 0;
  for (const auto& r : rows)
    if (r.what == "first_peak" && r.wall_s > 0) lo = lo == 0 ? r.N : std::min(lo, r.N), hi = std::max(hi, r.N);
  const double b = fitted_exponent(rows);
  char text[160];
  if (std::isfinite(b))
    std::snprintf(text, sizeof text, "time to the first peak ~ N^%.3g (least squares over N = %zu..%zu)", b, lo, hi);
  else
    std::snprintf(text, sizeof text,
                  "time to the first peak: no exponent from one size (N = %zu); give two sizes or more", lo);
  return text;
}

void write_interacting_bench(const fs::path& dir, const std::vector<InteractingBenchRow>& rows) {
  std::ostringstream o;
  o << "what,N,interaction_tolerance,wall_s,t_end_s,Q_s_N,A_s_m2,t_peak_s,steps,slips,repins,solves,chord_iterations,"
       "rank_one_updates,rebuilds,samples,max_rss_kB,N2_doubles_kB,single_passes,single_refreshes\n";
  for (const auto& r : rows)
    o << r.what << ',' << r.N << ',' << io::csv_number(r.interaction_tolerance) << ',' << io::csv_number(r.wall_s)
      << ',' << io::csv_number(r.t_end) << ',' << io::csv_number(r.Q_s) << ',' << io::csv_number(r.A_s) << ','
      << io::csv_number(r.t_peak) << ',' << r.steps << ',' << r.slips << ',' << r.repins << ',' << r.solves << ','
      << r.iterations << ',' << r.rank_one << ',' << r.rebuilds << ',' << r.samples << ',' << r.max_rss_kB << ','
      << io::csv_number(r.bound_kB) << ',' << r.single_passes << ',' << r.single_refreshes << '\n';
  fs::create_directories(dir);
  io::write_text_file(dir / "interacting.csv", o.str());
}

}  // namespace asperity

namespace asperity {

std::vector<InteractingTradeoffRow> run_interacting_tradeoff(const InteractingTradeoffOptions& opt) {
  auto scene_at = [&](double tol, double itol, double cutoff) {
    std::vector<std::string> o = opt.overrides;
    o.push_back(set_number("solver.tolerance", tol));
    o.push_back(set_number("solver.interaction_tolerance", itol));
    if (cutoff > 0) o.push_back(set_number("model.interaction_cutoff", cutoff));
    return load_scene(opt.scene, o);
  };
  std::vector<InteractingTradeoffRow> rows;
  auto add = [&](const std::string& knob, double tol, double itol, double cutoff,
                 const Observables* conv) -> const Observables {
    const TimedRun r = timed_run(scene_at(tol, itol, cutoff), opt.repeats);
    InteractingTradeoffRow row{knob, tol, itol, cutoff, r.wall_s, r.cpu_s, {}, {}};
    const auto v = robust_values(r.obs);
    row.value.assign(v.begin(), v.end());
    const auto e = conv ? relative_errors(r.obs, *conv) : std::array<double, n_robust>{};
    row.error.assign(e.begin(), e.end());
    rows.push_back(row);
    if (opt.log) {
      *opt.log << "  interacting " << knob << " tol " << tol << " interaction tol " << itol << " cutoff "
               << (cutoff > 0 ? std::to_string(cutoff * 1e3) + " mm" : "none") << ": " << r.wall_s << " s wall";
      for (std::size_t i = 0; i < n_robust && conv; ++i)
        if (std::isfinite(row.error[i])) *opt.log << ", " << robust_names()[i] << " err " << row.error[i];
      *opt.log << std::endl;
    }
    return r.obs;
  };
  const Observables conv = add("converged", opt.converged_tolerance, opt.converged_tolerance, 0, nullptr);
  const SolverSettings defaults = load_scene(opt.scene).solver;
  for (double tol : opt.tolerances) add("tolerance", tol, defaults.interaction_tolerance, 0, &conv);
  for (double itol : opt.interaction_tolerances) add("interaction_tolerance", defaults.tolerance, itol, 0, &conv);
  for (double c : opt.cutoffs_m) add("cutoff", defaults.tolerance, defaults.interaction_tolerance, c, &conv);
  return rows;
}

void write_interacting_tradeoff(const fs::path& dir, const std::vector<InteractingTradeoffRow>& rows) {
  std::ostringstream o;
  o << "knob,tolerance,interaction_tolerance,cutoff_m,wall_s,cpu_s";
  for (const auto& n : robust_names()) o << ',' << n << ',' << n << "_rel_error";
  o << '\n';
  for (const auto& r : rows) {
    o << r.knob << ',' << io::csv_number(r.tolerance) << ',' << io::csv_number(r.interaction_tolerance) << ','
      << io::csv_number(r.cutoff_m) << ',' << io::csv_number(r.wall_s) << ',' << io::csv_number(r.cpu_s);
    for (std::size_t i = 0; i < r.value.size(); ++i)
      o << ',' << io::csv_number(r.value[i]) << ','
        << (r.knob == "converged" ? std::string() : io::csv_number(r.error[i]));
    o << '\n';
  }
  fs::create_directories(dir);
  io::write_text_file(dir / "interacting_tradeoff.csv", o.str());
}

}  // namespace asperity
