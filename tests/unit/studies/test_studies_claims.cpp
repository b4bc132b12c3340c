// The verdict rules of REPORT.md (studies/claim_verdicts.hpp) on made-up observables: for every
// claim, one change at a time flips the verdict from reproduced to not reproduced and to no
// evidence; and the report says "no evidence" where a variant or a calibration failed.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "studies/claim_verdicts.hpp"
#include "studies/claims.hpp"
#include "support_scenes.hpp"

using namespace asperity;

namespace {

using V = Verdict;

Observables good_run() {
  Observables o;
  o.N = 100;
  o.A0 = 1e-6;
  o.dt = 1e-6;
  o.Q_s = 1.0;
  o.A_s = 0.85e-6;
  o.t_peak = 1.0;
  o.peak_found = true;
  o.alpha = 0.15e-6;
  o.alpha_R2 = 0.9;
  o.shape_exponent = 1.3;
  o.shape_exponent_measured = 1.9;
  o.area_drop_fraction = 0.15;
  o.ss_cycles = 5;
  o.ss_drop = 0.05;
  o.ss_period = 0.1;
  return o;
}

Observables without_stick_slip() {
  Observables o = good_run();
  o.ss_cycles = 0;
  o.ss_drop = o.ss_period = Observables::nan;
  return o;
}

AreaComparison good_comparison() {
  AreaComparison a;
  a.alpha_b = 0.7e-15;
  a.decay_model = 0.15;
  a.decay_measured = 0.16;
  a.slope_model = -0.30e-6;
  a.slope_measured = -0.32e-6;
  a.n_model = 1.3;
  a.n_measured = 1.9;
  return a;
}

// Stick-slip up to η = 150, none from 180 on: the bracket (150, 180].
LoadObservables good_load(const std::string& name) {
  LoadObservables l;
  l.experiment = name;
  l.base = good_run();
  l.base_eta = 100;
  for (double eta : {0.0, 50.0, 150.0}) l.eta_scan.emplace_back(eta, good_run());
  for (double eta : {180.0, 200.0, 250.0}) l.eta_scan.emplace_back(eta, without_stick_slip());
  l.c_min_low = good_run();
  Observables eq = good_run();
  eq.alpha_R2 = 0.99999;
  eq.shape_exponent = 2.0;
  l.equal_areas = eq;
  l.circular = good_run();
  l.area_law_always = good_run();
  l.at_scene_alpha_b = good_comparison();
  l.calibrated = good_comparison();
  return l;
}

ClaimObservables good_claims() {
  ClaimObservables c;
  for (const char* name : {"small", "mid", "large"}) c.loads.push_back(good_load(name));
  Observables ref = good_run();
  ref.slips = 87;
  ref.max_f_over_sigmaA = 0.99997;
  ref.max_f_over_sigma_exp_A = 1.111;
  c.reference = ref;
  return c;
}

std::optional<Observables>& eta_run(LoadObservables& l, double eta) {
  for (auto& [e, o] : l.eta_scan)
    if (e == eta) return o;
  FAIL("no eta " << eta);
  throw;  // unreachable
}

}  // namespace

TEST_CASE("combine: one counter-example decides, then a gap, else reproduced", "[claims]") {
  CHECK(combine(std::vector<V>{V::reproduced, V::reproduced}) == V::reproduced);
  CHECK(combine(std::vector<V>{V::reproduced, V::no_evidence}) == V::no_evidence);
  CHECK(combine(std::vector<V>{V::no_evidence, V::not_reproduced, V::reproduced}) == V::not_reproduced);
  CHECK(combine(std::vector<V>{}) == V::no_evidence);
  CHECK(std::string(verdict_text(V::no_evidence)) == "No evidence");
}

TEST_CASE("Claim 1: dt of the mid loads", "[claims]") {
  ClaimObservables c = good_claims();
  CHECK(claim1_dt(c) == V::reproduced);
  c.loads[0].base.dt = 5e-6;  // the smallest load is not a mid load
  CHECK(claim1_dt(c) == V::reproduced);
  c.loads[1].base.dt = 1.5e-6;
  CHECK(claim1_dt(c) == V::not_reproduced);
  c.loads[1].base.dt = Observables::nan;
  CHECK(claim1_dt(c) == V::no_evidence);
  ClaimObservables two = good_claims();
  two.loads.pop_back();  // no mid load
  CHECK(claim1_dt(two) == V::no_evidence);
}

TEST_CASE("Claim 2: stick-slip at every load", "[claims]") {
  ClaimObservables c = good_claims();
  CHECK(claim2_stick_slip(c) == V::reproduced);
  c.loads[2].base = without_stick_slip();
  CHECK(claim2_stick_slip(c) == V::not_reproduced);
  c.loads[2].past_first_peak = false;  // stopped at its first peak: could not show it
  CHECK(claim2_stick_slip(c) == V::no_evidence);
  c.loads[2].past_first_peak = true;
  c.loads[2].base.peak_found = false;  // never reached its peak
  CHECK(claim2_stick_slip(c) == V::no_evidence);
  ClaimObservables d = good_claims();
  d.loads[0].base_eta = 300;  // stick-slip, but not at the claim's η = 100
  CHECK(claim2_stick_slip(d) == V::no_evidence);
}

TEST_CASE("Claim 3, first half: eta = 50 against the base eta = 100", "[claims]") {
  ClaimObservables c = good_claims();
  CHECK(claim3_eta50_vs_base(c).verdict == V::reproduced);
  CHECK(claim3_eta50_vs_base(c).loading_diff == 0);
  SECTION("the peak differs by 2 %") {
    eta_run(c.loads[1], 50)->Q_s *= 1.02;
    const EtaComparison e = claim3_eta50_vs_base(c);
    CHECK(e.verdict == V::not_reproduced);
    CHECK(e.loading_diff == Approx(0.02).epsilon(1e-12));
  }
  SECTION("the stick-slip drop differs by 10 %") {
    eta_run(c.loads[1], 50)->ss_drop *= 1.1;
    CHECK(claim3_eta50_vs_base(c).verdict == V::not_reproduced);
  }
  SECTION("stick-slip at eta = 50 only") {
    c.loads[0].base = without_stick_slip();
    CHECK(claim3_eta50_vs_base(c).stick_slip_diff == std::numeric_limits<double>::infinity());
    CHECK(claim3_eta50_vs_base(c).verdict == V::not_reproduced);
  }
  SECTION("the eta = 50 run failed at one load") {
    eta_run(c.loads[2], 50).reset();
    CHECK(claim3_eta50_vs_base(c).verdict == V::no_evidence);
  }
  SECTION("the base run is not at eta = 100") {
    c.loads[0].base_eta = 120;  // cannot compare 50 with 100
    CHECK(claim3_eta50_vs_base(c).verdict == V::no_evidence);
  }
}

TEST_CASE("Claim 3, second half: the bracket where stick-slip vanishes, per load", "[claims]") {
  LoadObservables l = good_load("x");
  VanishBracket b = claim3_vanish_bracket(l);
  CHECK(b.last_with == 150);
  CHECK(b.first_without == 180);
  CHECK(b.verdict == V::reproduced);
  SECTION("vanishes between 100 and 150 (P6.40N on the stand-ins)") {
    eta_run(l, 150) = without_stick_slip();
    b = claim3_vanish_bracket(l);
    CHECK(b.last_with == 100);
    CHECK(b.first_without == 150);
    CHECK(b.verdict == V::not_reproduced);
  }
  SECTION("vanishes between 200 and 250: meets [162, 220]") {
    eta_run(l, 180) = good_run();
    eta_run(l, 200) = good_run();
    b = claim3_vanish_bracket(l);
    CHECK(b.last_with == 200);
    CHECK(b.first_without == 250);
    CHECK(b.verdict == V::reproduced);
  }
  SECTION("a grid point at 220 with stick-slip: (220, 250] is above the tolerance") {
    eta_run(l, 180) = good_run();
    eta_run(l, 200) = good_run();
    l.eta_scan.emplace_back(220.0, good_run());
    CHECK(claim3_vanish_bracket(l).verdict == V::not_reproduced);
  }
  SECTION("a grid point at 160 without stick-slip: (150, 160] is below the tolerance") {
    l.eta_scan.emplace_back(160.0, without_stick_slip());
    b = claim3_vanish_bracket(l);
    CHECK(b.first_without == 160);
    CHECK(b.verdict == V::not_reproduced);
  }
  SECTION("never vanishes") {
    for (auto& [eta, o] : l.eta_scan) o = good_run();
    b = claim3_vanish_bracket(l);
    CHECK(b.last_with == 250);
    CHECK(std::isinf(b.first_without));
    CHECK(b.verdict == V::not_reproduced);
  }
  SECTION("reappears above a gap: the bracket starts at the largest eta with stick-slip") {
    eta_run(l, 200) = good_run();
    b = claim3_vanish_bracket(l);
    CHECK(b.last_with == 200);
    CHECK(b.first_without == 250);
  }
  SECTION("one eta run failed") {
    eta_run(l, 250).reset();
    CHECK(claim3_vanish_bracket(l).verdict == V::no_evidence);
  }
  SECTION("the runs stopped at their first peak") {
    l.past_first_peak = false;
    CHECK(claim3_vanish_bracket(l).verdict == V::no_evidence);
  }
}

TEST_CASE("Claim 4: c_min = 1e-5 against 0.01", "[claims]") {
  ClaimObservables c = good_claims();
  CHECK(claim4_c_min(c).verdict == V::reproduced);
  SECTION("period differs by 2 %") {
    c.loads[1].c_min_low->ss_period *= 1.02;
    CHECK(claim4_c_min(c).verdict == V::not_reproduced);
    CHECK(claim4_c_min(c).diff == Approx(0.02).epsilon(1e-12));
  }
  SECTION("no stick-slip at c_min = 1e-5") {
    c.loads[1].c_min_low = without_stick_slip();
    CHECK(claim4_c_min(c).verdict == V::not_reproduced);
  }
  SECTION("missing") {
    c.loads[1].c_min_low.reset();
    CHECK(claim4_c_min(c).verdict == V::no_evidence);
  }
}

TEST_CASE("Claim 5: decay and slope need the calibration and the shape contrasts", "[claims]") {
  ClaimObservables c = good_claims();
  Claim5Verdicts v = claim5_calibrated(c);
  CHECK(v.decay == V::reproduced);
  CHECK(v.slope == V::reproduced);
  CHECK(v.shape == V::reproduced);
  SECTION("decay off by 30 %") {
    c.loads[0].calibrated->decay_model = 0.16 * 1.3;
    CHECK(claim5_calibrated(c).decay == V::not_reproduced);
    CHECK(claim5_calibrated(c).slope == V::reproduced);
  }
  SECTION("slope off by a factor 3 (the stand-ins)") {
    c.loads[0].calibrated->slope_model *= 3;
    CHECK(claim5_calibrated(c).slope == V::not_reproduced);
  }
  SECTION("calibration failed at one load: its decay and slope are no evidence, even if they would match") {
    c.loads[1].calibrated.reset();
    v = claim5_calibrated(c);
    CHECK(v.decay == V::no_evidence);
    CHECK(v.slope == V::no_evidence);
    CHECK(v.shape == V::reproduced);  // from the base run at that load
    c.loads[1].at_scene_alpha_b.n_model = 1.8;
    CHECK(claim5_calibrated(c).shape == V::not_reproduced);
  }
  SECTION("model quadratic") {
    c.loads[2].calibrated->n_model = 1.9;
    CHECK(claim5_calibrated(c).shape == V::not_reproduced);
  }
  SECTION("no measured curve") {
    c.loads[2].calibrated->n_measured = Observables::nan;
    c.loads[2].calibrated->decay_measured = Observables::nan;
    CHECK(claim5_calibrated(c).shape == V::no_evidence);
    CHECK(claim5_calibrated(c).decay == V::no_evidence);
  }
}

TEST_CASE("Claim 6: equal areas give a quadratic A(Q)", "[claims]") {
  LoadObservables l = good_load("x");
  CHECK(claim6_equal_areas(l) == V::reproduced);
  l.equal_areas->alpha_R2 = 0.99;
  CHECK(claim6_equal_areas(l) == V::not_reproduced);
  l.equal_areas->peak_found = false;  // the fit would not stop at macroscopic sliding
  CHECK(claim6_equal_areas(l) == V::no_evidence);
  l.equal_areas.reset();
  CHECK(claim6_equal_areas(l) == V::no_evidence);
}

TEST_CASE("Claim 7: f over sigma A from the reference window", "[claims]") {
  ClaimObservables c = good_claims();
  CHECK(claim7_forces(c) == V::reproduced);
  c.reference->max_f_over_sigmaA = 1.001;
  CHECK(claim7_forces(c) == V::not_reproduced);
  c.reference->max_f_over_sigmaA = 0.9;
  c.reference->max_f_over_sigma_exp_A = 0.99;  // never exceeds sigma_exp A
  CHECK(claim7_forces(c) == V::not_reproduced);
  c.reference->slips = 0;  // nothing slipped in the window
  CHECK(claim7_forces(c) == V::no_evidence);
  c.reference.reset();
  CHECK(claim7_forces(c) == V::no_evidence);
}

TEST_CASE("Claim 8: quasi-linear with circular junctions and area law always", "[claims]") {
  LoadObservables l = good_load("x");
  CHECK(claim8_shape_robust(l) == V::reproduced);
  l.circular->shape_exponent = 1.7;
  CHECK(claim8_shape_robust(l) == V::not_reproduced);
  l.circular->shape_exponent = 1.3;
  l.base.shape_exponent = 1.7;
  CHECK(claim8_shape_robust(l) == V::not_reproduced);
  l.base.shape_exponent = 1.3;
  l.area_law_always.reset();
  CHECK(claim8_shape_robust(l) == V::no_evidence);
}

TEST_CASE("REPORT.md says no evidence for a failed variant and a failed calibration", "[claims]") {
  std::vector<PaperRun> base;
  for (std::size_t n : {20, 30, 40}) {
    PaperRun r;
    r.scene = testing::paper_scene(testing::spread_areas(n, 1e-9, 1e-7));
    r.scene.experiment.name = "E" + std::to_string(n);
    r.obs = good_run();
    base.push_back(r);
  }
  std::vector<VariantRun> variants;
  for (const auto& b : base) {
    for (const char* label :
         {"eta=0", "eta=50", "eta=150", "eta=160", "c_min=1e-5", "equal_areas", "circular", "area_law=always"})
      variants.push_back({b.scene.experiment.name, label, good_run(), ""});
    for (const char* label : {"eta=180", "eta=200", "eta=220", "eta=250"})
      variants.push_back({b.scene.experiment.name, label, without_stick_slip(), ""});
  }
  variants[1].error = "solver gave up";  // E20 eta=50
  Calibration cal;
  cal.fit_file = "fits/x.yaml";
  for (const auto& b : base) {
    CalibratedRun c;
    c.experiment = b.scene.experiment.name;
    c.failure = "no confirmed static friction peak";
    cal.runs.push_back(c);
  }
  const ClaimObservables co = claim_observables(base, variants, cal);
  REQUIRE(co.loads.size() == 3);
  CHECK_FALSE(eta_run(const_cast<LoadObservables&>(co.loads[0]), 50).has_value());
  CHECK_FALSE(co.loads[0].calibrated.has_value());
  CHECK_FALSE(co.reference.has_value());
  const std::string md = claims_report(base, variants, cal, "");
  CHECK(md.find("First half: **No evidence**") != std::string::npos);
  // Claim 3's bracket per load: E20 lacks its eta = 50 run, the others have the whole scan.
  CHECK(md.find("| E20 | 5 (0.050) | – | 5 (0.050) | 5 (0.050) | 5 (0.050) | 0 (–) | 0 (–) | 0 (–) | 0 (–) | (160, "
                "180] | No evidence |") != std::string::npos);
  CHECK(md.find("| (160, 180] | Reproduced |") != std::string::npos);
  CHECK(md.find("Second half: **No evidence**") != std::string::npos);
  CHECK(md.find("**Calibration of E20 failed**") != std::string::npos);
  CHECK(md.find("**Area decay: No evidence. Incipient slope: No evidence.") != std::string::npos);
  CHECK(md.find("| E20 | 0.725 | **no** |") != std::string::npos);  // the scene's alpha_b, said so
  CHECK(md.find("No reference run in this reproduction.") != std::string::npos);
  CHECK(md.find("- E20 eta=50: solver gave up") != std::string::npos);
  // Claim 7 without its run is no evidence, not "not reproduced".
  const auto c7 = md.find("## 7.");
  REQUIRE(c7 != std::string::npos);
  CHECK(md.find("**No evidence**", c7) < md.find("## 8.", c7));
}
