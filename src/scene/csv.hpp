#pragma once
// Junction and measured-curve CSV files: a header row naming the columns (any order), then one
// number per field in plain SI units. '#' lines are comments; blank lines are allowed before
// the header and at the end of the file only. Unknown or duplicate columns are errors.
//   junctions: area_m2 (required, > 0), x_m and y_m (optional, together)
//   measured:  Q_N (>= 0), A_m2 (> 0), both required
//   force:     t_s (>= 0, strictly increasing), Q_N (any finite), both required, >= 2 rows
// Errors are InputError naming file, line, column and column name.
#include <filesystem>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace asperity {

// A measured tangential force history Q(t) (optional; a fit names it per experiment with
// `force:`, objective area_and_force): times strictly increasing from >= 0, forces finite.
struct MeasuredForce {
  std::vector<double> t_s, Q_N;
};

JunctionPopulation read_junctions_csv(const std::filesystem::path& csv);
MeasuredCurve read_measured_csv(const std::filesystem::path& csv);
MeasuredForce read_force_csv(const std::filesystem::path& csv);

// Deterministic bytes: '\n' line endings, shortest round-trip numbers (reading back gives the
// same doubles bit for bit). Written atomically (io/atomic_file.hpp, no fsync).
// Throws std::runtime_error when the file cannot be written, std::invalid_argument when the
// columns differ in length (x_m/y_m must be empty or as long as area_m2).
void write_junctions_csv(const std::filesystem::path& csv, const JunctionPopulation& junctions);
void write_measured_csv(const std::filesystem::path& csv, const MeasuredCurve& curve);
// `comment`: lines written first, each prefixed with "# " (provenance); may be empty.
void write_force_csv(const std::filesystem::path& csv, const MeasuredForce& force,
                     const std::vector<std::string>& comment = {});

// The one rule for a junction's values, whether from a CSV row or from columns given in memory
// (a scene's inline experiment.junctions): "" when allowed, else the message.
std::string junction_area_problem(double area_m2);        // must be in [1e-20, 1] m^2
std::string junction_coordinate_problem(double coord_m);  // |x|, |y| <= kMaxJunctionCoordinate_m
// The same for a measured curve's values.
std::string measured_force_problem(double Q_N);  // >= 0
std::string measured_area_problem(double A_m2);  // > 0

// Same readers, naming `display` in errors (the path as the referring file spells it).
JunctionPopulation read_junctions_csv(const std::filesystem::path& csv, const std::string& display);
// The same, with the line of each junction's row in `lines` (for errors found later: overlaps).
JunctionPopulation read_junctions_csv(const std::filesystem::path& csv, const std::string& display,
                                      std::vector<int>& lines);
MeasuredCurve read_measured_csv(const std::filesystem::path& csv, const std::string& display);
MeasuredForce read_force_csv(const std::filesystem::path& csv, const std::string& display);

}  // namespace asperity
