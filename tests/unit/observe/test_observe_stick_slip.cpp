#include <catch2/catch.hpp>
#include <cmath>

#include "observe/recorder.hpp"
#include "observe/stick_slip.hpp"

using namespace asperity;

namespace {
// A sawtooth of extrema: peak j at t = t0 + j·T with Q = Qs − j·0.01, trough Q_peak − drop.
// A junction slips before the first peak and the slider sticks after every trough.
void feed_sawtooth(Recorder& rec, int n_peaks, double t0, double T, double Qs, double drop) {
  rec.population({0.5 * t0, 1, false, 0});
  for (int j = 0; j < n_peaks && !rec.done(); ++j) {
    const double tp = t0 + j * T, Qp = Qs - 0.01 * j;
    rec.extremum({tp, Qp, 1e-5, true});
    rec.extremum({tp + 0.2 * T, Qp - drop, 1e-5, false});
    rec.population({tp + 0.3 * T, 0, true, 0});
  }
}
}  // namespace

TEST_CASE("stick-slip stats on a synthetic sequence of extrema", "[observe]") {
  Recorder rec(1e-3, false, 1e-3, false, -1);
  feed_sawtooth(rec, 8, 0.1, 0.13, 1.0, 0.12);
  REQUIRE(rec.peaks().size() == 8);
  const StickSlipStats s = stick_slip_stats(rec.peaks());
  CHECK(s.n_cycles == 5);
  CHECK(s.mean_drop == Approx(0.12).epsilon(1e-14));
  CHECK(s.mean_period == Approx(0.13).epsilon(1e-14));

  const StickSlipStats all = stick_slip_stats(rec.peaks(), 100);
  CHECK(all.n_cycles == 7);
}

TEST_CASE("stick-slip stats average the first n cycles only", "[observe]") {
  std::vector<Peak> p;
  // drops 1, 2, 3, 4; periods 1, 2, 3
  double t = 0;
  for (int j = 0; j < 4; ++j) {
    p.push_back({{t, 10.0, 0, true}, {t + 0.1, 10.0 - (j + 1), 0, false}});
    t += j + 1;
  }
  const StickSlipStats s2 = stick_slip_stats(p, 2);
  CHECK(s2.n_cycles == 2);
  CHECK(s2.mean_drop == Approx(1.5).epsilon(1e-14));
  CHECK(s2.mean_period == Approx(1.5).epsilon(1e-14));
  const StickSlipStats s5 = stick_slip_stats(p, 5);
  CHECK(s5.n_cycles == 3);  // the 4th peak closes the 3rd cycle; its own drop has no period
  CHECK(s5.mean_drop == Approx(2.0).epsilon(1e-14));
  CHECK(s5.mean_period == Approx(2.0).epsilon(1e-14));
}

TEST_CASE("stick-slip stats are NaN without a complete cycle", "[observe]") {
  std::vector<Peak> p;
  StickSlipStats s = stick_slip_stats(p);
  CHECK(s.n_cycles == 0);
  CHECK(std::isnan(s.mean_drop));
  CHECK(std::isnan(s.mean_period));
  p.push_back({{0.1, 1.0, 0, true}, {0.2, 0.8, 0, false}});
  s = stick_slip_stats(p);
  CHECK(s.n_cycles == 0);
  CHECK(std::isnan(s.mean_drop));
}

TEST_CASE("Recorder confirms a stick-slip peak after the first one only beyond min_drop", "[observe]") {
  Recorder rec(1e-3, false, 0.01, false, -1);
  rec.population({0.01, 1, false, 0});
  rec.extremum({0.05, 0.900, 0, true});
  rec.extremum({0.06, 0.800, 0, false});
  rec.population({0.07, 0, true, 0});
  REQUIRE(rec.peaks().size() == 1);
  rec.extremum({0.10, 1.000, 0, true});
  rec.extremum({0.11, 0.995, 0, false});  // 0.5 % < 1 %: precursor, not a peak
  CHECK(rec.peaks().size() == 1);
  rec.extremum({0.12, 0.998, 0, true});   // lower maximum: the candidate stays at 1.000
  rec.extremum({0.13, 0.991, 0, false});  // 0.9 % below the candidate: still not
  CHECK(rec.peaks().size() == 1);
  rec.extremum({0.14, 1.050, 0, true});   // a higher maximum replaces it
  rec.extremum({0.15, 1.030, 0, false});  // 1.9 % below: confirmed
  REQUIRE(rec.peaks().size() == 2);
  CHECK(rec.peaks()[1].max.t == 0.14);
  CHECK(rec.peaks()[1].min.t == 0.15);
  CHECK(rec.highest().Q == 1.050);
  CHECK_FALSE(rec.done());
}

TEST_CASE("Recorder stops at the first peak and cuts the loading branch there", "[observe]") {
  Recorder rec(0.01, true, 1e-3, true, -1);
  for (int i = 0; i <= 10; ++i) {
    const double t = 0.01 * i;
    REQUIRE(rec.next_sample_time() == Approx(t));
    rec.sample({t, 0, 0, 10.0 * t, 1e-5, 0, 0});
  }
  CHECK(rec.loading_branch().size() == 11);
  rec.population({0.05, 1, false, 1});
  rec.extremum({0.055, 0.6, 1e-5, true});
  CHECK_FALSE(rec.done());
  rec.extremum({0.09, 0.5, 1e-5, false});
  rec.population({0.092, 1, false, 0});  // the last junction gives way
  CHECK_FALSE(rec.done());
  rec.population({0.095, 0, true, 0});  // and the slider sticks
  CHECK(rec.done());
  REQUIRE(rec.peaks().size() == 1);
  // Samples after the peak time were dropped from the loading branch, kept in the series.
  CHECK(rec.loading_branch().size() == 6);
  CHECK(rec.loading_branch().back().t <= 0.055);
  CHECK(rec.series().size() == 11);
}

TEST_CASE("Recorder stops after the requested number of cycles", "[observe]") {
  Recorder rec(1e-3, false, 1e-3, false, 3);
  feed_sawtooth(rec, 10, 0.1, 0.1, 1.0, 0.1);
  CHECK(rec.done());
  CHECK(rec.peaks().size() == 4);  // 3 cycles need 4 peaks
  CHECK(stick_slip_stats(rec.peaks(), 3).n_cycles == 3);
}
