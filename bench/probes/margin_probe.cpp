// Probe (ASPERITY_PROBES builds it): how close the pinned junctions are to their slip
// thresholds on the way to the first peak, the premise of a solver that needs exact forces only
// near a threshold. On `bench interacting`'s first-peak row (the stand-in P4.00N's areas repeated
// to N), at every output sample (`every` seconds) the load ratios f_i / f_s,i of the pinned
// junctions (one extra exact solve per sample) are binned by their margin 1 − ratio. Prints, per
// margin bound δ, the mean and largest number of pinned junctions within δ of their threshold,
// and the mean number pinned. Build against a Release build in build/ and run from the
// repository root:
//   cmake -S . -B build -DASPERITY_PROBES=ON && ninja -C build margin_probe
//   build/margin_probe 1200 0.005
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "generate/positions.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"
#include "solve/interacting/interacting_event_stepper.hpp"
using namespace asperity;

struct MarginObserver {
  InteractingEventStepper* stepper = nullptr;
  double every = 0.005, next = 0, Q_max = 0;
  bool past_peak = false;
  static constexpr int kBounds = 5;
  const double bound[kBounds] = {1e-5, 1e-4, 1e-3, 1e-2, 1e-1};
  double sum[kBounds] = {}, pinned_sum = 0;
  std::int64_t most[kBounds] = {}, samples = 0;
  void sample(const Sample& s) {
    next = s.t + every;
    Q_max = std::max(Q_max, s.Q);
    auto& J = stepper->junctions();
    const std::vector<double> ratio = J.load_ratios(s.X);
    std::int64_t count[kBounds] = {}, pinned = 0;
    for (std::size_t i = 0; i < ratio.size(); ++i) {
      if (!J.state().pinned[i]) continue;
      ++pinned;
      for (int b = 0; b < kBounds; ++b) count[b] += 1.0 - ratio[i] < bound[b];
    }
    for (int b = 0; b < kBounds; ++b) sum[b] += count[b], most[b] = std::max(most[b], count[b]);
    pinned_sum += pinned;
    ++samples;
  }
  void extremum(const Extremum& e) { past_peak = past_peak || e.is_max; }
  void population(const PopulationChange&) {}
  bool done() const { return past_peak; }
  double next_sample_time() const { return next; }
};

int main(int argc, char** argv) {
  const std::size_t N = std::atoi(argv[1]);
  Scene base = load_scene("scenes/paper/P4.00N.yaml");
  const auto areas = base.experiment.junctions.area_m2;
  Scene s = base;
  s.experiment.junctions.area_m2.resize(N);
  for (std::size_t i = 0; i < N; ++i) s.experiment.junctions.area_m2[i] = areas[i % areas.size()];
  s.experiment.mass_kg = base.experiment.mass_kg * double(N) / double(areas.size());
  s.stop.time = 60;
  s.stop.wall_time = 7200;
  const Positions p = place_in_contact_disc(s.experiment.junctions.area_m2,
                                            4.5e-3 * std::sqrt(double(N) / double(areas.size())), 20200318);
  s.experiment.junctions.x_m = p.x_m, s.experiment.junctions.y_m = p.y_m;
  s.model.interactions = Interactions::elastic;
  const Problem problem = make_problem(s);
  InteractingEventStepper stepper(problem);
  MarginObserver obs;
  obs.stepper = &stepper;
  obs.every = argc > 2 ? std::atof(argv[2]) : 0.005;
  integrate(stepper, problem, obs);
  std::printf("N,margin_bound,mean_pinned_within,most_pinned_within,mean_pinned,samples\n");
  for (int b = 0; b < MarginObserver::kBounds; ++b)
    std::printf("%zu,%g,%.2f,%lld,%.1f,%lld\n", N, obs.bound[b], obs.sum[b] / obs.samples, (long long)obs.most[b],
                obs.pinned_sum / obs.samples, (long long)obs.samples);
}
