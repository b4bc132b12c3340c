#pragma once
// What the interaction study (studies/interactions.yaml) writes (interaction_study.hpp): table.csv, joint.csv,
// forces_at_peak.csv, the force-spread figure and REPORT.md, from the rows its runs filled and the
// verdicts of interaction_verdicts.hpp. The sections taken from other studies' files (the
// recovery matrix, the sweep store, the topography table) are read here, as REPORT.md is written.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "studies/interaction_study.hpp"
#include "studies/interaction_verdicts.hpp"

namespace asperity::interaction_detail {

// The force spread at the first peak of one experiment (the paper's Figure 2 argument):
// f_i/(σA_i) of every junction in both models, its crowding, and the set of equal area.
struct Spread {
  bool ran = false;
  std::string experiment;
  double area_lo = 0, area_hi = 0, crowding_median = 0;
  std::vector<double> A0, x, y, crowding, ratio_inter, ratio_indep;  // at the peak
  std::vector<double> half_inter, half_indep;                        // at half its time
  std::vector<std::uint8_t> equal;                                   // in the equal-area set
  Scene inter, indep;  // the runs: interacting, and the same arrangement 10⁶ wider
  double t_peak_inter = NAN, t_peak_indep = NAN;
};

// table.csv: one row per model and experiment that ran.
void write_table_csv(const std::filesystem::path& out, const std::vector<StudyRow>& rows);

// forces_at_peak.csv: every junction's f/(σA) in both models, its crowding and position.
void write_forces_csv(const std::filesystem::path& out, const Spread& sp);

// The figure of the force spread; a note when gnuplot could not draw it (empty otherwise).
std::string draw_force_spread(const InteractionStudyOptions& opt, const Spread& sp);

// joint.csv: one row per model and load with a joint calibration that ran.
void write_joint_csv(const std::filesystem::path& out, const std::vector<JointRow>& rows);

// OUT/REPORT.md: the verdict (`verdict`, from `tally`) and the joint calibrations' (`joint_text`),
// the recovery matrix, the tables of both models per load, the force spread (the note of its
// figure, the pairs' section) and the tables read from the sweep store and the topography study.
void write_report_md(const InteractionStudyOptions& opt, const std::vector<StudyRow>& rows, const Tally& tally,
                     const std::string& verdict, const std::vector<JointRow>& joint, const std::string& joint_text,
                     const Spread& sp, const std::string& fig_note, const std::string& pairs_md);

}  // namespace asperity::interaction_detail
