#include "bench/accuracy.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "bench/bench_scene.hpp"
#include "io/atomic_file.hpp"
#include "io/numbers.hpp"
#include "observe/simulate.hpp"

#include "bench/number_text.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {
using bench_text::exact;
using io::format_significant;
}  // namespace

bool AccuracyRow::within_targets() const {
  for (std::size_t i = 0; i < n_robust; ++i)
    if (!(error[i] < robust_targets()[i])) return false;
  return true;
}

AccuracyRow accuracy_row(const std::string& experiment, double tolerance, const Observables& run,
                         const Observables& converged) {
  AccuracyRow r;
  r.experiment = experiment;
  r.tolerance = tolerance;
  r.wall_s = run.wall_s;
  r.converged_wall_s = converged.wall_s;
  r.cycles = run.ss_cycles;
  r.converged_cycles = converged.ss_cycles;
  r.value = robust_values(run);
  r.converged = robust_values(converged);
  r.error = relative_errors(run, converged);
  return r;
}

std::vector<AccuracyRow> run_accuracy(const AccuracyOptions& opt) {
  std::vector<AccuracyRow> rows;
  const std::size_t total = opt.scenes.size() * (1 + std::max<std::size_t>(1, opt.tolerances.size()));
  std::size_t done = 0;
  const auto ran = [&] {
    if (opt.on_run) opt.on_run(++done, total);
  };
  for (const fs::path& path : opt.scenes) {
    std::vector<std::string> o = opt.overrides;
    o.push_back("output.series=[]");
    o.push_back("solver.method=event");
    const Scene scene = bench_scene(path, o);
    auto oc = o;
    oc.push_back(set_number("solver.tolerance", opt.converged_tolerance));
    const RunResult conv = simulate(bench_scene(path, oc));
    ran();
    std::vector<double> tols = opt.tolerances;
    if (tols.empty()) tols.push_back(scene.solver.tolerance);
    for (double tol : tols) {
      auto ot = o;
      ot.push_back(set_number("solver.tolerance", tol));
      const RunResult run = simulate(bench_scene(path, ot));
      ran();
      rows.push_back(accuracy_row(scene.experiment.name, tol, run.obs, conv.obs));
      if (opt.log) {
        const auto& r = rows.back();
        *opt.log << "  " << r.experiment << " (stand-in) tol " << format_significant(r.tolerance) << " vs "
                 << format_significant(opt.converged_tolerance) << ", " << r.cycles << " cycles, "
                 << format_significant(r.wall_s, 3) << " s:";
        for (std::size_t i = 0; i < n_robust; ++i)
          *opt.log << ' ' << robust_names()[i] << ' ' << format_significant(r.error[i], 2);
        *opt.log << (r.within_targets() ? "  (within targets)" : "  (TARGET MISSED)") << '\n' << std::flush;
      }
    }
  }
  return rows;
}

std::string accuracy_csv(const std::vector<AccuracyRow>& rows) {
  std::ostringstream o;
  o << "experiment,tolerance,wall_s,converged_wall_s,cycles,converged_cycles";
  for (const auto& n : robust_names()) o << ",value_" << n;
  for (const auto& n : robust_names()) o << ",converged_" << n;
  for (const auto& n : robust_names()) o << ",relerr_" << n;
  o << ",within_targets\n";
  for (const auto& r : rows) {
    o << r.experiment << ',' << format_significant(r.tolerance) << ',' << format_significant(r.wall_s, 4) << ','
      << format_significant(r.converged_wall_s, 4) << ',' << r.cycles << ',' << r.converged_cycles;
    for (double x : r.value) o << ',' << exact(x);
    for (double x : r.converged) o << ',' << exact(x);
    for (double x : r.error) o << ',' << format_significant(x, 4);
    o << ',' << (r.within_targets() ? "yes" : "no") << '\n';
  }
  return o.str();
}

void write_accuracy(const fs::path& dir, const std::vector<AccuracyRow>& rows) {
  fs::create_directories(dir);
  io::write_text_file(dir / "accuracy.csv", accuracy_csv(rows));
}

}  // namespace asperity
