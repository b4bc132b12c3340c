// studies/claim_variants.hpp: the variant list and run_variants against direct runs of the
// changed scenes (the same observables, bit for bit, whatever the order of the parallel jobs).
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "observe/simulate.hpp"
#include "studies/claim_variants.hpp"
#include "support_scenes.hpp"

using namespace asperity;

TEST_CASE("claim variants: the eta scan, then one variant per other claim", "[claims]") {
  const std::vector<ClaimVariant> v = paper_claim_variants();
  REQUIRE(v.size() == kClaimEtaScan.size() + 5);
  std::set<std::string> labels;
  for (const ClaimVariant& x : v) labels.insert(x.label);
  CHECK(labels.size() == v.size());  // labels are keys of the report
  CHECK(eta_variant_label(180) == "eta=180");
  CHECK(eta_variant_label(0) == "eta=0");
  CHECK(v.front().label == "eta=0");
  CHECK(v.back().label == kReferenceVariantLabel);
  CHECK_FALSE(v.back().all_experiments);  // the reference window runs on the first experiment only
  Scene s;
  v[4].apply(s);  // kClaimEtaScan[4] = 180
  CHECK(s.model.eta == 180.0);
}

TEST_CASE("run_variants gives the observables of running each changed scene directly", "[claims]") {
  Scene a = testing::paper_scene(testing::spread_areas(8, 1e-9, 4e-9));
  a.stop.time = 0.05;
  Scene b = a;
  b.experiment.name = "second";
  b.experiment.mass_kg = 0.6;
  const std::vector<ClaimVariant> variants{
      {"eta=50", [](Scene& s) { s.model.eta = 50; }},
      {"first only", [](Scene& s) { s.model.c_min = 1e-5; }, false},
  };
  const std::vector<VariantRun> runs = run_variants({a, b}, variants, 2);
  REQUIRE(runs.size() == 3);  // 2 experiments × eta=50, 1 × "first only"
  int checked = 0;
  for (const VariantRun& r : runs) {
    CHECK(r.error.empty());
    Scene s = r.experiment == "second" ? b : a;
    for (const ClaimVariant& v : variants)
      if (v.label == r.label) v.apply(s);
    s.output.series.clear();
    const Observables direct = simulate(s).obs;
    CHECK(r.obs.Q_s == direct.Q_s);
    CHECK(r.obs.steps == direct.steps);
    CHECK(std::isfinite(direct.Q_s));
    checked += r.label == "first only" ? (r.experiment == "test" ? 10 : 100) : 1;
  }
  CHECK(checked == 12);  // both experiments ran eta=50; only the first ran "first only"
}
