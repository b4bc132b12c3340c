#include "report/fit_figures.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

#include "io/hash.hpp"
#include "io/numbers.hpp"
#include "report/gnuplot.hpp"
#include "report/units.hpp"

namespace asperity {

// File-name stem for an experiment (names are free text). A name made only of letters, digits,
// '.', '-' and '_' (not starting with '.', at most 80 bytes) is its own stem; any other name gets
// its other bytes replaced by '_' and "+" and the FNV-1a 64 hash of the whole name appended, so
// that "x y" and "x_y" (or two long names with a common start) never share files. '+' is not in
// the plain set, so a hashed stem never equals a plain one.
std::string fit_file_stem(const std::string& name) {
  const auto plain = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_';
  };
  const bool as_is =
      !name.empty() && name.size() <= 80 && name.front() != '.' && std::all_of(name.begin(), name.end(), plain);
  if (as_is) return name;
  std::string s;
  for (char c : name.substr(0, 60)) s += plain(c) ? c : '_';
  if (!s.empty() && s.front() == '.') s.front() = '_';
  return s + "+" + io::hex16(io::fnv1a64(name));
}

// The tic format of an axis spanning the values `v`: as many digits as tell tics about a fifth
// of the span apart (gnuplot's default keeps too few for a narrow span far from zero, e.g. a
// profile of α_b ± 10 %, and repeats one label), short %g otherwise ("7.2e-16", not "7.2x10^{-16}").
std::string tic_format(const char* axis, const std::vector<double>& v) {
  double lo = INFINITY, hi = -INFINITY;
  for (const double x : v)
    if (std::isfinite(x)) lo = std::min(lo, x), hi = std::max(hi, x);
  int digits = 3;
  if (hi > lo)
    digits = std::clamp(
        static_cast<int>(std::ceil(std::log10(std::max(std::abs(lo), std::abs(hi)) / ((hi - lo) / 5)))) + 1, 3, 12);
  return std::string("set format ") + axis + " '%." + std::to_string(digits) + "g'\n";
}

std::vector<double> profile_values(const std::vector<ProfilePoint>& points) {
  std::vector<double> v;
  for (const auto& p : points) v.push_back(p.value);
  return v;
}

namespace {

// The objective along one profiled parameter, from its CSV.
std::string profile_figure(const std::string& label, const std::string& key, const std::string& stem,
                           const std::vector<ProfilePoint>& points, const std::string& ext) {
  std::ostringstream gp;
  gp << "set output " << gnuplot_quote(stem + ext) << "\n"
     << "set title " << title_lines(label + ": objective around the optimum,") << " . \"\\n\" . "
     << gnuplot_quote(column_symbol(key)) << " . " << gnuplot_quote(" varied (others fixed)") << "\nset xlabel "
     << gnuplot_quote(axis_markup(key)) << "\nset ylabel 'objective [1] (dimensionless)'\nset key off\n"
     << "set rmargin 6\n"  // room for the last x tic label
     << tic_format("x", profile_values(points)) << tics_for_span("x", gnuplot_quote(stem + ".csv") + " skip 1", "2")
     << "plot " << gnuplot_quote(stem + ".csv")
     << " skip 1 using 2:($3 == $3 ? $3 : 1/0) with linespoints pt 7 lw 1.5\n"
     << "set rmargin -1\nset format x '% h'\nset xtics autofreq\n";
  return gp.str();
}

// What an objective measures, in a reader's words (its key, objective_name, is the file's).
std::string objective_words(FitObjective o) {
  switch (o) {
    case FitObjective::quadratic_alpha:
      return "A(Q)'s quadratic coefficient";
    case FitObjective::area_curve:
      return "A(Q) curve";
    case FitObjective::stick_slip:
      return "stick-slip drop and period";
    case FitObjective::area_and_force:
      return "chi-square of A(Q) and Q(t)";
    case FitObjective::user:
      return "the caller's objective";
  }
  return "objective";
}

// The objective over the evaluations, and its best so far.
std::string convergence_figure(const FitSpec& spec, const Optimization& o, const std::string& ext) {
  const std::string col = std::to_string(o.variables.size() + 2);
  std::ostringstream gp;
  gp << "set output " << gnuplot_quote("convergence" + ext) << "\n"
     << "set title "
     << title_lines(spec.name + " / " + o.label + ": objective (" + objective_words(spec.objective) + ")")
     << " . \"\\n\" . " << title_lines(spec.algorithm + ", stop " + o.stop_reason) << "\n"
     << "set xlabel 'evaluation number'\nset ylabel 'objective [1] (dimensionless)'\nset logscale y\n"
     << "set key bottom left Left reverse\n"  // the corner a falling objective leaves empty
     << "best = 1e300\n"
     << "plot 'evaluations.csv' skip 1 using 1:($" << col << " > 0 ? $" << col
     << " : 1/0) with linespoints pt 7 ps 0.6 title 'objective', "
     << "'' skip 1 using 1:(($" << col << " > 0 && $" << col << " < best) ? (best = $" << col
     << ") : best) with steps lw 2 title 'best so far'\n"
     << "unset logscale y\n";
  return gp.str();
}

// Each experiment's Q(t) (area_and_force) and A(Q) at the fit, with its measurement.
std::string experiment_figures(const FitSpec& spec, const Optimization& o, const std::string& ext) {
  const std::string area_scale = io::format_double(figure_unit("A").scale);
  std::ostringstream gp;
  for (const auto& r : o.best_runs) {
    if (!r.force) continue;
    const std::string name = spec.experiments[r.experiment].name;
    const std::string qstem = "Qt_" + fit_file_stem(name);
    gp << "set output " << gnuplot_quote(qstem + ext) << "\n"
       << "set title " << title_lines(name + ": Q(t) at the fit") << "\nset xlabel " << gnuplot_quote(axis_markup("t"))
       << "\nset ylabel " << gnuplot_quote(axis_markup("Q")) << "\nset key top left Left reverse\n"
       << tics_for_span("x", gnuplot_quote(qstem + "_model.csv") + " skip 1", "1") << "plot "
       << gnuplot_quote(qstem + "_measured.csv") << " skip 1 using 1:2 with points pt 7 ps 0.3 title '"
       << (r.stand_in ? "stand-in measurement" : "measurement") << "', " << gnuplot_quote(qstem + "_model.csv")
       << " skip 1 using 1:2 with lines lw 1.5 title 'model (fitted)'\nset xtics autofreq\n";
  }
  for (const auto& r : o.best_runs) {
    const std::string name = spec.experiments[r.experiment].name;
    const std::string stem = "AQ_" + fit_file_stem(name);
    gp << "set output " << gnuplot_quote(stem + ext) << "\n"
       << "set title " << title_lines(name + ": A(Q) on the loading branch at the fit") << "\nset xlabel "
       << gnuplot_quote(axis_markup("Q")) << "\nset ylabel " << gnuplot_quote(axis_markup("A"))
       << "\nset key bottom left Left reverse\n"
       << tics_for_span("x", gnuplot_quote(stem + "_model.csv") + " skip 1", "1") << "plot "
       << gnuplot_quote(stem + "_model.csv") << " skip 1 using 1:($2*" << area_scale
       << ") with lines lw 2 title 'model (fitted)'";
    if (r.measured)
      gp << ", " << gnuplot_quote(stem + "_measured.csv") << " skip 1 using 1:($2*" << area_scale
         << ") with points pt 7 ps 0.7 title '" << (r.stand_in ? "stand-in measurement" : "measurement") << "'";
    gp << "\nset xtics autofreq\n";
  }
  return gp.str();
}

}  // namespace

std::string optimization_figures(const FitSpec& spec, const Optimization& o, const std::string& ext) {
  std::string gp = convergence_figure(spec, o, ext);
  if (!o.profile.empty())
    gp += profile_figure(o.label, spec.parameters[o.profile_parameter].key, "profile", o.profile, ext);
  for (std::size_t q = 1; q < o.profiles.size(); ++q) {
    const std::string& key = spec.parameters[o.profiles[q].parameter].key;
    gp += profile_figure(o.label, key, "profile_" + fit_file_stem(key), o.profiles[q].points, ext);
  }
  return gp + experiment_figures(spec, o, ext);
}

}  // namespace asperity
