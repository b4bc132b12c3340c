// Probe (ASPERITY_PROBES builds it): one `bench interacting` first-peak row (the stand-in P4.00N's
// areas repeated to N, placed as the bench places them, no output series) with the solver's work
// counters, for side-by-side runs of two builds of the solver (issue 26). Build against a Release
// build in build/ and run from the repository root:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build first_peak_probe
//   OMP_NUM_THREADS=1 build/first_peak_probe 1200 [interaction_tolerance [wall_limit_s]]
// With a wall limit the run stops there (stop.wall_time, counted after the set-up: the coupling
// matrix and its first factorisation, whose time it prints) and prints how far it got.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include "generate/positions.hpp"
#include "observe/recorder.hpp"
#include "observe/simulate.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"
#include "solve/interacting/interacting_event_stepper.hpp"
using namespace asperity;
int main(int argc, char** argv) {
  const std::size_t N = std::atoi(argv[1]);
  Scene base = load_scene("scenes/paper/P4.00N.yaml");  // run from the repository root
  const auto areas = base.experiment.junctions.area_m2;
  const std::size_t N0 = areas.size();
  Scene s = base;
  s.experiment.junctions.area_m2.resize(N);
  for (std::size_t i = 0; i < N; ++i) s.experiment.junctions.area_m2[i] = areas[i % N0];
  s.experiment.mass_kg = base.experiment.mass_kg * double(N) / double(N0);
  s.stop.at_first_peak = true;
  s.stop.time = 60;
  s.stop.wall_time = 7200;
  s.output.series.clear();
  const double R = 4.5e-3 * std::sqrt(double(N) / double(N0));
  const Positions p = place_in_contact_disc(s.experiment.junctions.area_m2, R, 20200318);
  s.experiment.junctions.x_m = p.x_m;
  s.experiment.junctions.y_m = p.y_m;
  s.model.interactions = Interactions::elastic;
  s.solver.method = SolverMethod::event;
  if (argc > 2) s.solver.interaction_tolerance = std::atof(argv[2]);
  if (argc > 3) s.stop.wall_time = std::atof(argv[3]);
  const Problem problem = make_problem(s);
  Recorder rec = make_recorder(s);
  auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<InteractingEventStepper> made;
  try {
    made = std::make_unique<InteractingEventStepper>(problem);
  } catch (const WallTimeReached&) {  // the wall limit ran out in the set-up's first event search
    std::printf("N %zu: stopped by the wall limit in the set-up after %.3f s\n", N,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    return 0;
  }
  InteractingEventStepper& stepper = *made;
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const RunInfo info = integrate(stepper, problem, rec);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto w = stepper.junctions().work();
  const FirstPeak fp = rec.first_peak();
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  std::printf("set-up %.3f s, max RSS %.0f MB, t_end %.6g s, stopped by a limit: %s\n", setup, ru.ru_maxrss / 1024.0,
              info.t_end, info.stopped_by == LimitHit::none ? "no" : "yes");
  std::printf(
      "N %zu tol %g wall %.3f s  Q_s %.17g t_peak %.17g A_s %.17g steps %lld slips %lld solves %lld iters %lld rank1 "
      "%lld rebuilds %lld single %lld refresh %lld\n",
      N, s.solver.interaction_tolerance, wall, fp.max.Q, fp.max.t, fp.max.A, (long long)info.stats.steps,
      (long long)info.stats.slips, (long long)w.solves, (long long)w.iterations, (long long)w.rank_one,
      (long long)w.rebuilds, (long long)w.single_passes, (long long)w.single_refreshes);
}
