// observe/run_monitor.hpp through simulate(): a monitor sees the run's progress and can
// interrupt it; watching changes no number.
#include <catch2/catch.hpp>
#include <vector>

#include "observe/simulate.hpp"
#include "support_scenes.hpp"

using namespace asperity;
using namespace asperity::testing;

TEST_CASE("a monitor that lets the run go changes nothing and sees simulated time advance", "[observe][monitor]") {
  Scene s = paper_scene(spread_areas(200, 1e-10, 5e-9));
  s.stop.time = 0.5;
  const RunResult plain = simulate(s);

  std::vector<double> seen;
  RunMonitor m;
  m.period_s = 0;  // poll every 64th step
  m.poll = [&](double t, double t_end) {
    CHECK(t_end == 0.5);
    seen.push_back(t);
    return true;
  };
  const RunResult watched = simulate(s, 0, &m);
  CHECK(watched.info.stats.slips == plain.info.stats.slips);
  CHECK(watched.info.t_end == plain.info.t_end);
  CHECK(watched.obs.Q_s == plain.obs.Q_s);
  CHECK(watched.recorder.series().size() == plain.recorder.series().size());
  REQUIRE(seen.size() >= 3);
  for (std::size_t i = 1; i < seen.size(); ++i) CHECK(seen[i] >= seen[i - 1]);
  CHECK(seen.back() <= 0.5);
}

TEST_CASE("a monitor that says stop interrupts the run early", "[observe][monitor]") {
  Scene s = paper_scene(spread_areas(200, 1e-10, 5e-9));
  s.stop.time = 1.0;
  int polls = 0;
  RunMonitor m;
  m.period_s = 0;
  m.poll = [&](double t, double) {
    ++polls;
    return t < 0.1;
  };
  REQUIRE_THROWS_AS(simulate(s, 0, &m), RunInterrupted);
  // Stopped at the first poll past 0.1 s, far before stop.time (the run needs ~10^4 steps).
  CHECK(polls >= 2);
  Scene again = s;
  int polls_again = 0;
  m.poll = [&](double t, double) {
    ++polls_again;
    return t < 0.1;
  };
  CHECK_THROWS_WITH(simulate(again, 0, &m), Catch::Contains("run interrupted at simulated t = "));
}
