#pragma once
// Files of `asperity regress`:
//   suite  (scenes/regression/suite.yaml): what is run —
//     entries:
//       - {name: P0.98N_stick_slip, scene: ../paper/P0.98N.yaml, set: [stop.cycles=5]}
//     (scene paths relative to the suite file; `set` as `asperity run --set`)
//   golden (results/regression/golden.yaml): what came out when last blessed, with a tolerance
//     per observable, and the history of blessings (date, version, reason). An entry or an
//     observable given twice, or an observable regress_observables does not compute, is an
//     InputError at its line.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace asperity {

struct RegressEntry {
  std::string name;
  std::filesystem::path scene;         // resolved
  std::vector<std::string> overrides;  // "key=value"
};

struct RegressSuite {
  std::filesystem::path file;
  std::vector<RegressEntry> entries;
};

struct GoldenValue {
  double value = 0;
  double tolerance = 0;  // absolute; |now − value| ≤ tolerance passes
};

struct GoldenRecord {
  std::string date, version, reason;
};

struct Golden {
  std::vector<GoldenRecord> history;
  // entry name → observable name → value
  std::map<std::string, std::map<std::string, GoldenValue>> entries;
};

RegressSuite load_regress_suite(const std::filesystem::path& yaml);  // InputError on bad input
Golden load_golden(const std::filesystem::path& yaml);               // InputError on bad input
std::string golden_to_yaml(const Golden& g);                         // exact round trip

}  // namespace asperity
