// A fit stopped mid-way (FitOptions::stop: the command line's Ctrl-C, the Python module's)
// abandons the evaluations in flight: none may be scored, journaled or reported as a failure.
// Its starts run in parallel; a stop that ended one start's evaluation used to cancel, through
// TBB's task contexts, the runs of another start's evaluation, which then scored NaN
// ("objective is not finite") and went into the journal as a failed point (the resumed fit
// would have replayed it as a failure). batch/parallel_runner.cpp isolates nested loops.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <string_view>
#include <thread>

#include "fit/fit.hpp"
#include "fit/fit_load.hpp"
#include "observe/run_monitor.hpp"

using namespace asperity;

TEST_CASE("a fit stopped mid-way scores no evaluation it abandoned", "[fit][stop]") {
  // The stand-in P6.40N of the six-load joint fit: runs of about 0.5 s, six starts in parallel.
  const FitSpec spec = load_fit(std::string(ASPERITY_SOURCE_DIR) + "/fits/joint_independent.yaml");
  int interrupted = 0;
  for (const int ms : {150, 450, 750, 1050}) {
    std::atomic<bool> flag{false};
    FitOptions o;
    o.threads = 2;
    o.profile = false;
    o.only = {0};
    o.stop = &flag;
    std::atomic<int> evaluations{0}, not_finite{0};
    o.on_evaluation = [&](const FitTick& t) {
      ++evaluations;
      if (std::string_view(t.part) != "done" && !std::isfinite(t.objective)) ++not_finite;
    };
    std::thread stopper([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(ms));
      flag = true;
    });
    try {
      run_fit(spec, o);
    } catch (const RunInterrupted&) {
      ++interrupted;
    }
    stopper.join();
    INFO("stopped after " << ms << " ms: " << evaluations.load() << " evaluations");
    CHECK(not_finite.load() == 0);
  }
  CHECK(interrupted == 4);
}
