// The measured choice of a parallel loop's threads (solve/core/adaptive_team.hpp) and the
// kernel form a run uses (solve/interacting/kernel_form.hpp), driven with synthetic timings and
// environments: what the policy does is decided by its inputs, not by this machine's load.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

#include "io/input_error.hpp"
#include "solve/core/adaptive_team.hpp"
#include "solve/interacting/kernel_form.hpp"

using namespace asperity;

namespace {

// Runs `regions` regions of unit work through the team, each taking `wide_s` on the whole team
// and `narrow_s` on one thread; returns the time spent and counts the wide regions.
double drive(AdaptiveTeam& team, int regions, double wide_s, double narrow_s, int& wide) {
  double spent = 0;
  wide = 0;
  for (int k = 0; k < regions; ++k) {
    const int t = team.choose(1.0);
    const double s = t > 1 ? wide_s : narrow_s;
    wide += t > 1;
    team.record(t, s, 1.0);
    spent += s;
  }
  return spent;
}

}  // namespace

TEST_CASE("adaptive team: the cheaper choice wins, a change of load is followed, probes cost at most a few percent",
          "[solve][adaptive_team]") {
  AdaptiveTeam team(2, 0.5);
  int wide = 0;
  // Quiet: two threads take 60 % of one thread's time; nearly every region runs wide.
  double spent = drive(team, 2000, 60e-6, 100e-6, wide);
  CHECK(wide >= 1990);
  CHECK(spent <= 1.01 * 2000 * 60e-6);
  // Busy: a region on two threads now waits for a time slice (3 ms against 0.1 ms on one).
  // Measured: 6 regions on two threads, 1.009x the one-thread time.
  // Within a few regions the team runs on one thread, and the probes of two threads cost at
  // most 1/20 of the time (plus the regions before the switch).
  spent = drive(team, 20000, 3e-3, 100e-6, wide);
  const double one_thread = 20000 * 100e-6;
  INFO("busy: " << wide << " regions on two threads, " << spent / one_thread << "x the one-thread time");
  CHECK(wide <= 20);
  CHECK(spent <= 1.03 * one_thread);
  // Quiet again: two threads are taken back within about kLongestWait (1 s) of measured time.
  int regions = 0;
  for (; regions < 20000 && team.choose(1.0) == 1; ++regions) team.record(1, 100e-6, 1.0);
  INFO("regions until two threads were tried again: " << regions);
  CHECK(regions * 100e-6 <= 1.05);
  spent = drive(team, 2000, 60e-6, 100e-6, wide);
  CHECK(wide >= 1990);
}

TEST_CASE("adaptive team: one thread below the work threshold or with a team of one", "[solve][adaptive_team]") {
  AdaptiveTeam small(2, 100.0);
  CHECK(small.choose(99.0) == 1);
  small.record(1, 1.0, 99.0);
  CHECK(small.narrow_regions() == 0);  // not measured
  CHECK(small.seconds() == 1.0);       // but timed
  AdaptiveTeam one(1, 0.0);
  for (int k = 0; k < 10; ++k) CHECK(one.choose(1e9) == 1);
}

TEST_CASE("kernel form: ASPERITY_KERNEL picks any form this CPU has and refuses others in one line",
          "[solve][pinned][kernel_form]") {
  const char* before = std::getenv("ASPERITY_KERNEL");
  const std::string saved = before ? before : "";
  const auto forms = kernel_forms_available();
  REQUIRE(forms.front() == KernelForm::portable);
  unsetenv("ASPERITY_KERNEL");
  CHECK(kernel_form() == forms.back());
  setenv("ASPERITY_KERNEL", "auto", 1);
  CHECK(kernel_form() == forms.back());
  for (KernelForm f : forms) {
    setenv("ASPERITY_KERNEL", kernel_form_name(f), 1);
    CHECK(kernel_form() == f);
  }
  setenv("ASPERITY_KERNEL", "sse9", 1);
  try {
    kernel_form();
    FAIL("an unknown form was taken");
  } catch (const io::InputError& e) {
    CHECK(e.key == "ASPERITY_KERNEL");
    CHECK(std::string(e.what()).find("'sse9' is not a kernel form") != std::string::npos);
  }
  if (forms.size() < 3) {  // a form this CPU lacks
    setenv("ASPERITY_KERNEL", "avx512", 1);
    CHECK_THROWS_AS(kernel_form(), io::InputError);
  }
  if (before)
    setenv("ASPERITY_KERNEL", saved.c_str(), 1);
  else
    unsetenv("ASPERITY_KERNEL");
}
