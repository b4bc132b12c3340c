#include "solve/core/run_limits.hpp"

#include <algorithm>
#include <cmath>

#include "io/numbers.hpp"
#include "physics/interface_law.hpp"

namespace asperity {

std::int64_t default_max_slips(const Scene& scene) {
  const double per_junction = 1e4 * std::max(1.0, scene.stop.time);
  const double n = 1e6 + per_junction * static_cast<double>(scene.experiment.junctions.size());
  return n < 9e18 ? static_cast<std::int64_t>(n) : std::numeric_limits<std::int64_t>::max();
}

RunLimits run_limits(const Scene& scene) {
  RunLimits l;
  l.wall_time_s = scene.stop.wall_time;
  l.max_slips = scene.stop.max_slips > 0 ? scene.stop.max_slips : default_max_slips(scene);
  return l;
}

namespace {

// Smallest distance (1 − ε) f_s / k the slider travels between a repin and the next slip of a
// junction (at its first-slip area), and that junction's area.
std::pair<double, double> smallest_slip_distance(const Scene& scene) {
  const ContactLaw law = make_contact_law(scene.experiment, scene.model);
  double best = std::numeric_limits<double>::infinity(), area = 0;
  for (double A0 : scene.experiment.junctions.area_m2) {
    const JunctionContact c = contact_at_first_slip(law, A0);
    const double d = (1.0 - law.epsilon) * law.sigma * c.area_m2 / c.k;
    if (d < best) best = d, area = A0;
  }
  return {best, area};
}

}  // namespace

std::string limit_message(const Scene& scene, const RunLimits& limits, LimitHit hit, double t_end, std::int64_t slips) {
  const std::string at =
      " at simulated t = " + io::format_short(t_end) + " s of " + io::format_short(scene.stop.time) + " s";
  if (hit == LimitHit::wall_time)
    return "stop.wall_time: run stopped after " + io::format_short(limits.wall_time_s) + " s of wall time" + at +
           " (raise stop.wall_time, or look for what makes it slow: solver.tolerance, model.eta, "
           "a huge population)";
  std::string m = "stop.max_slips: run stopped after " + std::to_string(slips) + " slips" + at;
  if (scene.stop.max_slips > 0) return m + " (raise stop.max_slips if that many are expected)";
  // The default limit is far above what any physical run needs: name the usual cause.
  const auto [d, area] = smallest_slip_distance(scene);
  m += " (the default: 10^6 + 10^4 per junction and simulated second; set stop.max_slips if that many are "
       "expected); a junction that slips while the slider is slower than c_min*v repins at once and slips again "
       "after (1 - epsilon) f_s/k of travel: the smallest such distance here is " +
       io::format_short(d) + " m (junction of " + io::format_short(area) +
       " m^2); check the junction areas and sigma_exp";
  return m;
}

}  // namespace asperity
