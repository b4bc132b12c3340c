#pragma once
// The runs the paper's claims need beyond the base runs (docs/model.md §6): an η scan, c_min, equal
// areas, the circular junction shape, the other area law and a window of the reference solver,
// each a change to a copy of a base scene, run in parallel.
#include <functional>
#include <string>
#include <vector>

#include "observe/observables.hpp"
#include "scene/scene.hpp"

namespace asperity {

struct ClaimVariant {
  std::string label;                  // e.g. "eta=180"
  std::function<void(Scene&)> apply;  // modifies a copy of the base scene
  bool all_experiments = true;        // false: on the first (smallest) experiment only
};

struct VariantRun {
  std::string experiment, label;
  Observables obs;
  std::string error;  // non-empty when the run failed
};

// The variants docs/model.md §6 needs beyond the base runs.
std::vector<ClaimVariant> paper_claim_variants();

// Runs every variant on the base scenes (TBB, `threads` workers). Failures are recorded.
// `done` (optional, thread-safe) is called after each run with the number finished and the total.
std::vector<VariantRun> run_variants(const std::vector<Scene>& base, const std::vector<ClaimVariant>& variants,
                                     int threads,
                                     const std::function<void(std::size_t done, std::size_t total)>& done = {});

// Claim 3's η scan beside the base runs' η = 100 (1/s). 160 and 220 sit at the edges of the
// claim's range [162, 220] (ClaimRules): every bracket is then inside or outside it, never
// straddling it because the grid is coarse.
inline const std::vector<double> kClaimEtaScan{0.0, 50.0, 150.0, 160.0, 180.0, 200.0, 220.0, 250.0};
std::string eta_variant_label(double eta);  // "eta=180": the label of that scan's variant
inline constexpr const char* kReferenceVariantLabel = "reference Ct=100, 0.25 s";  // claim 7's window

}  // namespace asperity
