// Peaks of two curves paired by time (observe/peak_pairing.hpp) against the costs' closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "observe/peak_pairing.hpp"

using namespace asperity;

namespace {

// A peak at t_cross = t whose drop stands `excess` above its fall.
SampledPeak peak(double t, double drop, double fall) {
  SampledPeak p;
  p.t_max = t - 0.001, p.t_cross = t;
  p.Q_max = 1.0, p.Q_min = 1.0 - drop;
  p.trough_seen = true, p.fall_N = fall;
  return p;
}

// Five main slips of drop 0.3 every 0.1 s from t = 0.1 s; their falls 0.02.
std::vector<SampledPeak> main_slips(double shift_s = 0, double drop = 0.3) {
  std::vector<SampledPeak> v;
  for (int k = 1; k <= 5; ++k) v.push_back(peak(0.1 * k + shift_s, drop, 0.02));
  return v;
}

PeakPairingScale unit_scale() {
  PeakPairingScale s;
  s.sigma_t_s = 0.001, s.sigma_drop_N = 0.01, s.t_window_s = 10.0, s.taper_s = 0.05;
  return s;
}

}  // namespace

TEST_CASE("pair_peaks: equal lists pair one to one at no cost; a shift costs its square", "[observe][pairing]") {
  const PeakPairingScale s = unit_scale();
  const PeakPairing same = pair_peaks(main_slips(), main_slips(), s);
  CHECK(same.chi2 == 0.0);
  CHECK(same.pairs == 5);
  CHECK(same.unpaired_measured + same.unpaired_model == 0);
  // Every model peak 2 ms late and 0.01 N deeper: five pairs at (2² + 1²) each.
  const PeakPairing shifted = pair_peaks(main_slips(), main_slips(0.002, 0.31), s);
  CHECK(shifted.chi2 == Approx(5 * (4.0 + 1.0)).epsilon(1e-12));
  CHECK(shifted.pairs == 5);
}

TEST_CASE("pair_peaks: a marginal extra peak costs its excess over the threshold, not the pairing of all that follow",
          "[observe][pairing]") {
  const PeakPairingScale s = unit_scale();
  // The measured curve finds a precursor 15 ms before the first slip whose drop stands 0.004 N
  // (0.4 σ) above its fall. Paired by order every slip would meet its predecessor (100 ms apart:
  // 10⁴ each); paired by time the precursor alone is left, at 0.4².
  std::vector<SampledPeak> measured = main_slips();
  measured.insert(measured.begin(), peak(0.085, 0.024, 0.02));
  const PeakPairing p = pair_peaks(measured, main_slips(), s);
  CHECK(p.chi2 == Approx(0.16).epsilon(1e-12));
  CHECK(p.pairs == 5);
  CHECK(p.unpaired_measured == 1);
  CHECK(p.unpaired_model == 0);
  // The same precursor on the model's side costs the same, and a peak found with no excess at all
  // (where it appears) costs nothing: the score is continuous as it appears.
  CHECK(pair_peaks(main_slips(), measured, s).chi2 == Approx(0.16).epsilon(1e-12));
  measured.front() = peak(0.085, 0.02, 0.02);
  CHECK(pair_peaks(measured, main_slips(), s).chi2 == Approx(0.0).margin(1e-20));
}

TEST_CASE("pair_peaks: a pairing too far apart in time costs both peaks unpaired instead", "[observe][pairing]") {
  const PeakPairingScale s = unit_scale();
  // One slip each, 50 ms apart: paired (50)² = 2,500; unpaired 2 · ((0.3 − 0.02)/0.01)² = 1,568.
  const std::vector<SampledPeak> a{peak(0.1, 0.3, 0.02)}, b{peak(0.15, 0.3, 0.02)};
  const PeakPairing p = pair_peaks(a, b, s);
  CHECK(p.chi2 == Approx(2 * 28.0 * 28.0).epsilon(1e-12));
  CHECK(p.pairs == 0);
  // 30 ms apart the pair is cheaper: 900.
  CHECK(pair_peaks(a, std::vector<SampledPeak>{peak(0.13, 0.3, 0.02)}, s).chi2 == Approx(900.0).epsilon(1e-12));
}

TEST_CASE("pair_peaks: an unpaired peak fades linearly before the window's end", "[observe][pairing]") {
  PeakPairingScale s = unit_scale();
  s.t_window_s = 0.6, s.taper_s = 0.1;
  // The model's sixth slip at t = 0.58 s has no measured partner: weight (0.6 − 0.58)/0.1 = 0.2 of
  // its 28²; at t = 0.65 s (past the window) it costs nothing.
  std::vector<SampledPeak> model = main_slips();
  model.push_back(peak(0.58, 0.3, 0.02));
  CHECK(pair_peaks(main_slips(), model, s).chi2 == Approx(0.2 * 28.0 * 28.0).epsilon(1e-12));
  model.back() = peak(0.65, 0.3, 0.02);
  CHECK(pair_peaks(main_slips(), model, s).chi2 == 0.0);
  // Empty lists: nothing to pay; a deviation that is not positive is refused.
  CHECK(pair_peaks({}, {}, s).chi2 == 0.0);
  s.sigma_t_s = 0;
  CHECK_THROWS_AS(pair_peaks(main_slips(), main_slips(), s), std::invalid_argument);
}
