#pragma once
// Junction-level evidence for the interaction study (the paper's Figure 2
// argument followed in time): pairs of junctions of equal area, one in a crowded and one in a
// sparse neighbourhood, and their force f_i(t) and contact area A_i(t) from the start of
// loading to past the first peak, with and without elastic interactions.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "report/gnuplot.hpp"
#include "scene/scene.hpp"

namespace asperity {

// One junction's history: force [N] and contact area [m²] at the sample times [s], and the
// time of its first slip (NaN: it never slipped before the run ended).
struct JunctionTrace {
  std::size_t junction = 0;                 // 0-based index in the scene's junctions
  std::vector<double> t_s, X_m, f_N, A_m2;  // X_m: the slider position
  double first_slip_s = NAN;
};

// Runs `scene` with the interacting event solver (model.interactions must be elastic; a wide
// position_scale makes it the independent model through the same code) to `t_end_s`, and
// records the force and area of each of `junctions` at n_samples + 1 equally spaced times
// (an exact solve of the junction forces at each).
std::vector<JunctionTrace> trace_junctions(const Scene& scene, const std::vector<std::size_t>& junctions,
                                           double t_end_s, int n_samples);

struct JunctionPair {
  std::size_t crowded = 0, sparse = 0;  // 0-based junction indices
};

// The k-th most crowded with the k-th least crowded of `candidates` (junctions of equal area),
// k = 0 … n_pairs − 1 (fewer when there are fewer than 2 n_pairs candidates).
std::vector<JunctionPair> crowded_sparse_pairs(std::vector<std::size_t> candidates, const std::vector<double>& crowding,
                                               std::size_t n_pairs);

// What the study shows of the pairs: the traces of every pair's junctions in both models.
struct JunctionPairsEvidence {
  std::string experiment;
  bool stand_in = false;  // the experiment is a stand-in (is_stand_in): the figure says so
  double sigma_Pa = 0;    // the interfacial shear strength σ of f/(σA)
  double t_peak_interacting_s = NAN, t_peak_independent_s = NAN;
  std::vector<JunctionPair> pairs;
  std::vector<double> A0_m2, crowding;                  // every junction's, by index
  std::vector<JunctionTrace> interacting, independent;  // pairs' junctions in order: crowded, sparse, …
};

// Writes OUT/junction_pairs.csv and OUT/junction_pairs.png (and the other `formats`; a failure to draw is returned as a
// note) and returns the report's section (markdown): per junction, the first slip time and
// f/(σA) and A/A0 at half the first peak's time and at it, in both models.
std::string write_junction_pairs(const std::filesystem::path& out, const JunctionPairsEvidence& e,
                                 const FigureFormats& formats);

}  // namespace asperity
