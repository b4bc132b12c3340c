// fit/fit.hpp's FitOptions::on_evaluation, progress and fit_run_budget: every evaluation a fit
// makes is told (its starts, the best point's re-run, the profile, the error-bar refits), the
// finished optimization gives back what it left of its budget, so the count ends exactly at the
// budget; one line per finished fit with its own best objective.
#include <catch2/catch.hpp>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "fit/fit.hpp"
#include "fit/fit_load.hpp"

using namespace asperity;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

TEST_CASE("fit progress: profile and refit runs are counted and the count ends at the budget", "[fit][progress]") {
  // Three small experiments, alpha_b alone, a 3-point profile and one error bar (E: two refits).
  const FitSpec spec = load_fit(std::filesystem::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "fit" / "fit.yaml");
  FitOptions o;
  o.threads = 2;
  o.only = {0};  // m010: about a second
  std::mutex m;
  std::map<std::string, int> runs;  // by part
  long long unused = 0;
  int finished = 0;
  o.on_evaluation = [&](const FitTick& t) {
    const std::lock_guard<std::mutex> lock(m);
    CHECK(*t.label == "m010");
    if (std::string_view(t.part) == "done") {
      unused += t.unused;
      ++finished;
    } else {
      ++runs[t.part];
    }
  };
  std::vector<std::string> lines;
  o.progress = [&](const std::string& line) { lines.push_back(line); };
  const FitResult r = run_fit(spec, o);
  REQUIRE(r.fits.size() == 1);
  const Optimization& f = r.fits[0];
  REQUIRE(f.ok());
  int refit_runs = 0;
  for (const ErrorBarRefit& rf : f.refits) refit_runs += rf.evaluations;
  CHECK(runs["fit"] == f.evaluations);
  CHECK(runs["best"] == 1);
  CHECK(runs["profile"] == 3);
  CHECK(runs["refit"] == refit_runs);
  CHECK(refit_runs > 0);
  CHECK(runs.count("hessian") == 0);  // quadratic_alpha: no intervals
  // The optimization's 40, the re-run, 3 profile points, 2 refits of 40 at most.
  const long long budget = fit_run_budget(spec, o);
  CHECK(budget == 40 + 1 + 3 + 2 * 40);
  CHECK(finished == 1);
  CHECK(f.evaluations + 1 + 3 + refit_runs + unused == budget);
  REQUIRE(lines.size() == 1);
  CHECK_THAT(lines[0],
             StartsWith("m010: best J = ") && Contains("converged: unverified (1 of 1 start(s) in the best basin)"));

  // Without profile and error bars neither is budgeted; over every experiment, three times one.
  FitOptions bare;
  bare.profile = bare.error_bars = false;
  CHECK(fit_run_budget(spec, bare) == 3 * (40 + 1));
}
