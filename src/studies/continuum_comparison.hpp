#pragma once
// `asperity study studies/continuum.yaml`: the junction models against the continuum they approximate, on the
// same contact map (docs/continuum.md). For a topography recipe at several loads: the normal
// contact (surface/normal_contact.hpp) gives the contact map and, through its clusters, the
// junctions (scene/topography_junctions.hpp); the continuum reference is the tangential contact on
// that map (surface/tangential_contact.hpp) with a constant shear strength σ = σ_exp per unit area;
// the junction models are independent and interacting discs (uniform and rigid weighting) on those
// junctions, quasi-statically (solve/quasi_static/junction_curve.hpp), with α_b = 0 and ε = 1 so
// that all four share the same physics except the elastic representation. Per load and model: the
// initial stiffness and its error, Q at 10 % and 50 % of the area slipping, the displacement of
// full sliding, the rms error of Q(δ), against the coverage, the stiffness ratio and the junction count.
// SYNTHETIC surfaces: every file says so.
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "report/gnuplot.hpp"

namespace asperity {

struct ContinuumStudyOptions {
  std::filesystem::path recipe;  // a topography recipe (its load_N is replaced by each load)
  std::vector<double> loads_N;
  std::filesystem::path out;
  std::filesystem::path study_file;  // the study file these options came from (provenance; may be empty)
  int points = 32;                   // displacements of each Q(δ), up to 1.25 × the continuum's full sliding
  double tolerance = 1e-8;           // of the tangential and junction solves (relative to δ)
  int threads = 1;                   // of the contact solves (the numbers do not depend on it)
  FigureFormats figures;
  std::ostream* log = nullptr;
};

struct ContinuumRow {
  double load_N = 0;
  std::size_t junctions = 0;
  double contact_area_m2 = 0;
  double pixels_per_junction = 0;  // contact pixels / junctions: how well the map resolves a junction
  double coverage_hertz = 0;       // contact area / π a_H², a_H Hertz's radius of the smooth sphere
  double coverage_population = 0;  // of the junctions (studies/continuum_rule.hpp, population_measures)
  double stiffness_ratio = 0;      // of the junctions (the same)
  std::string model;               // continuum, independent, interacting-uniform, interacting-rigid
  double initial_stiffness_N_per_m = 0;
  double stiffness_error = 0;  // relative to the continuum's (0 for it)
  double q10 = 0, q50 = 0;     // Q / Q_full when 10 % and 50 % of the contact area slips
  double full_sliding_displacement_m = 0;
  double full_sliding_error = 0;  // relative to the continuum's
  double rms_error = 0;           // rms of (Q − Q_continuum) / Q_full over the displacements
  bool converged = true, monotone = true;
};

struct ContinuumCurvePoint {
  double load_N = 0;
  std::string model;
  double displacement_m = 0, force_N = 0, slip_area_fraction = 0;
};

struct ContinuumStudy {
  std::vector<ContinuumRow> rows;
  std::vector<ContinuumCurvePoint> curves;
};

// Runs the comparison and writes OUT/table.csv, curves.csv, rule.csv, REPORT.md and the figures.
// InputError on a bad recipe or a contact that cannot be solved.
ContinuumStudy run_continuum_study(const ContinuumStudyOptions& options);

}  // namespace asperity
