#pragma once
// The interaction study's view of the topography study (results/topography/;
// SYNTHETIC surfaces): its table.csv, one row per surface realisation (seed), load and model,
// with the shape of that model's A(Q) there, read and tallied so that the interaction study's
// REPORT.md states what interactions change on junctions from contact mechanics
// from that table's own numbers. Absent table: no rows (no evidence).
#include <filesystem>
#include <string>
#include <vector>

namespace asperity {

struct TopographyShapeRow {
  int seed = 0;
  double load_N = 0;
  int junctions = 0;
  std::string model;                                 // "independent" or "interacting"
  double alpha_b = 0;                                // m⁵/N², calibrated to the stand-in drop
  double shape_exponent = 0;                         // n of A0 − A ∝ Qⁿ
  double endpoint_residual = 0;                      // rms of A(Q) off A0(1 − d (Q/Q_s)²), units A0 d
  double residual_rms_m2 = 0, noise_rms_p95_m2 = 0;  // against a noisy parabola, and the noise's 95 %
  bool within_noise() const { return residual_rms_m2 <= noise_rms_p95_m2; }
};

// Reads `file` (the columns above by their table.csv names; others ignored). No file: no rows.
// A row without the columns, or a field that is not a finite number where one is needed, throws
// InputError at its line and column.
std::vector<TopographyShapeRow> read_topography_table(const std::filesystem::path& file);

// Loads (seed and load) where both models ran: interacting minus independent.
struct TopographyTally {
  int pairs = 0;
  double mean_dn = 0, min_dn = 0, max_dn = 0;  // shape exponent
  int n_lower = 0;                             // pairs where interactions lower n
  double max_abs_dres = 0;                     // endpoint residual, largest |difference|
  int rows = 0, within_noise = 0;              // every row (either model), and those within noise
};
TopographyTally tally_topography(const std::vector<TopographyShapeRow>& rows);

}  // namespace asperity
