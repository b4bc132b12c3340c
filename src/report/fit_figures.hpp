#pragma once
// The figures of a fit's results folder (report/fit_writer.hpp) as gnuplot script, and the file
// names and tic formats they share with the folder's tables and fitted.png.
#include <string>
#include <vector>

#include "fit/fit.hpp"
#include "fit/fit_spec.hpp"

namespace asperity {

// File-name stem of an experiment's files (names are free text; see the .cpp).
std::string fit_file_stem(const std::string& name);

// gnuplot's `set format AXIS` for the values `v`: digits enough that tics a fifth of the span
// apart differ.
std::string tic_format(const char* axis, const std::vector<double>& v);

std::vector<double> profile_values(const std::vector<ProfilePoint>& points);

// One format's figures of an optimization (its terminal set before): convergence, the profiles,
// each experiment's Q(t) and A(Q) at the fit, drawn from the CSVs beside them; `ext` the
// format's file extension.
std::string optimization_figures(const FitSpec& spec, const Optimization& o, const std::string& ext);

}  // namespace asperity
