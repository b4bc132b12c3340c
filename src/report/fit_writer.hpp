#pragma once
// The results directory of a fit (results/fits/<name>/):
//   fit.yaml          fitted values, objective, NLopt stop reason, evaluations, wall times, the
//                     best run's observables per experiment, profile and error-bar ranges;
//   fitted.csv        one row per (optimization, experiment): fitted values and observables;
//   evaluations.csv   every evaluation: values, objective, per-experiment terms, status;
//   convergence.png   objective against evaluation (and best so far);
//   profile.csv/.png  the objective around the optimum, one parameter varied;
//   AQ_<exp>.png      A(Q): model loading branch at the fit against the measured samples,
//   AQ_<exp>_model.csv, AQ_<exp>_measured.csv  the plotted data.
// A joint fit writes these in DIR; separate fits write evaluations..AQ into DIR/<experiment>/.
// DIR is built as a temporary sibling and renamed into place; an existing DIR is replaced only
// when it holds a fit.yaml (never unrelated files). PNGs are skipped without gnuplot. The fit's
// journals (journal.csv, inputs.txt, tasks/: fit/fit_journal.hpp) are carried over into the new
// folder.
#include <filesystem>
#include <string>

#include "fit/fit.hpp"
#include "fit/fit_spec.hpp"
#include "report/gnuplot.hpp"  // FigureFormats

namespace asperity {

std::string fit_yaml(const FitSpec& spec, const FitResult& result, const std::string& command_line = "");

// The figures in each format of `figures` (--figures; PNG alone by default).
void write_fit(const std::filesystem::path& dir, const FitSpec& spec, const FitResult& result,
               const std::string& command_line = "", const FigureFormats& figures = {});

// Throws the error write_fit would give for an existing `dir` that is not a fit directory.
void check_fit_dir(const std::filesystem::path& dir);

// check_fit_dir, then makes `dir` (with the fit's marker) when absent: the journal lives there
// while the fit runs (report/output_dir.hpp, claim_dir).
void claim_fit_dir(const std::filesystem::path& dir);

}  // namespace asperity
