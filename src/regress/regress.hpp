#pragma once
// Regression runs: a curated suite of scenes, run and compared with blessed golden values.
// Tolerances are not guessed: each entry also runs with a tighter solver setting (event:
// tolerance/100 and interaction_tolerance/100; reference: 2·C_t), and an observable may move by 10× the change that
// tightening causes, or by 10× the solver tolerance relative (whichever is larger; the
// reference, first order in dt, by 1e-12 relative), since that is how far a change of
// rounding (another compiler, another machine) can move it.
#include <map>
#include <string>
#include <vector>

#include "observe/observables.hpp"
#include "regress/regress_io.hpp"

namespace asperity {

// The compared observables, by name (counts as doubles).
std::map<std::string, double> regress_observables(const Observables& o);
// Names of observables that are counts (compared exactly unless tightening changes them).
bool regress_is_count(const std::string& name);

struct RegressResult {
  std::string name;
  std::map<std::string, double> values, tight;  // at the scene's settings / tightened
  double solver_rel_floor = 0;                  // 10·tolerance (event) or 1e-12 (reference)
  std::string error;                            // non-empty when the run failed
  double wall_s = 0;
};

// Runs every entry (and its tightened twin when `tight`) on `threads` workers.
std::vector<RegressResult> run_regress_suite(const RegressSuite& suite, bool tight, int threads);

// New golden values from results that include their tightened twins.
Golden bless(const std::vector<RegressResult>& results, std::vector<GoldenRecord> history);

struct Drift {
  std::string entry, observable;
  double golden = 0, now = 0, tolerance = 0;
  bool ok = true;
  std::string note;  // "missing in golden", "run failed: ...", ...
};
// One row per compared value (ok or not).
std::vector<Drift> compare(const Golden& golden, const std::vector<RegressResult>& results);

}  // namespace asperity
