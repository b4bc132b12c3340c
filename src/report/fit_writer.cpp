#include "report/fit_writer.hpp"
#include "report/gnuplot.hpp"
#include "report/output_dir.hpp"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "io/csv.hpp"
#include "io/hash.hpp"
#include "io/numbers.hpp"
#include "io/provenance.hpp"
#include "report/fit_figures.hpp"
#include "report/run_writer.hpp"
#include "report/units.hpp"
#include "scene/input_files.hpp"
#include "scene/load.hpp"

namespace asperity {

namespace fs = std::filesystem;

namespace {

// Numbers of the fit tables: %.17g round-trips, "nan" for NaN (gnuplot and CSV readers parse it).
using io::format_g17;
constexpr double kGravity = 9.81;  // m/s², P = M g (as the stand-in recipe)

// Draws the fit's figures from the CSVs beside them; the script is kept as `gp_name` in the
// folder (`gnuplot NAME.gp` there redraws them).
// The fit figures: 800 × 560 pixels (PNG), one journal column (SVG, PDF).
constexpr int kFitPlotWidth = 800, kFitPlotHeight = 560;

void plot_quietly(const fs::path& dir, const std::string& script, const std::string& gp_name) {
  keep_plot_script(dir / gp_name,
                   "# asperity plot script: `gnuplot " + gp_name + "` redraws this fit's figures\n" + script);
  try {
    io::run_gnuplot(dir, script);
  } catch (const std::exception&) {  // a failed plot is not a failed fit
  }
}

struct Range {
  double value = Observables::nan, min = Observables::nan, max = Observables::nan, sigma = Observables::nan;
};

// Per variable: the range of the fitted value over the fit and all error-bar refits, and the
// combined one-sigma change: quadrature sum over quantities of half the ± difference.
std::vector<Range> error_bar_ranges(const Optimization& o) {
  std::vector<Range> out(o.variables.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    Range& r = out[i];
    r.value = r.min = r.max = o.best[i];
    double s2 = 0;
    bool complete = true;
    for (std::size_t k = 0; k < o.refits.size(); ++k) {
      const double x = o.refits[k].best[i];
      if (!std::isfinite(x)) {
        complete = false;
        continue;
      }
      r.min = std::min(r.min, x);
      r.max = std::max(r.max, x);
      if (o.refits[k].sign < 0)
        for (const auto& q : o.refits)
          if (q.key == o.refits[k].key && q.sign > 0 && std::isfinite(q.best[i]))
            s2 += std::pow(0.5 * (q.best[i] - x), 2);
    }
    r.sigma = complete ? std::sqrt(s2) : Observables::nan;
  }
  return out;
}

std::string fit_subdir(const FitSpec& spec, const Optimization& o) {
  return spec.separate ? fit_file_stem(o.label) : std::string();
}

std::string evaluations_csv(const Optimization& o, const FitSpec& spec) {
  std::ostringstream c;
  c << "evaluation";
  for (const auto& v : o.variables) c << "," << io::csv_field(v.label);
  c << ",objective";
  for (const auto e : o.experiments) c << "," << io::csv_field("term_" + spec.experiments[e].name);
  c << ",wall_s,status\n";
  for (const auto& ev : o.log) {
    c << ev.index;
    for (const double x : ev.values) c << "," << format_g17(x);
    c << "," << format_g17(ev.objective);
    for (std::size_t k = 0; k < o.experiments.size(); ++k)
      c << "," << format_g17(k < ev.residuals.size() ? ev.residuals[k] : Observables::nan);
    c << "," << format_g17(ev.wall_s) << "," << io::csv_field(ev.status) << "\n";
  }
  return c.str();
}

std::string profile_csv(const std::vector<ProfilePoint>& points) {
  std::ostringstream c;
  c << "factor,value,objective,status\n";
  for (const auto& p : points)
    c << format_g17(p.factor) << "," << format_g17(p.value) << "," << format_g17(p.objective) << ","
      << io::csv_field(p.status) << "\n";
  return c.str();
}

// A Q_N,A_m2 or t_s,Q_N table of two columns.
template <class Row>
std::string two_columns(const char* header, std::size_t n, Row row) {
  std::ostringstream t;
  t << header << "\n";
  for (std::size_t k = 0; k < n; ++k) {
    const auto [x, y] = row(k);
    t << format_g17(x) << "," << format_g17(y) << "\n";
  }
  return t.str();
}

// The tables of one optimization: evaluations, profiles, and each experiment's curves at the fit.
void write_optimization_tables(const fs::path& d, const FitSpec& spec, const Optimization& o) {
  io::write_text_file(d / "evaluations.csv", evaluations_csv(o, spec));
  if (!o.profile.empty()) io::write_text_file(d / "profile.csv", profile_csv(o.profile));
  // Every further profiled parameter: profile_<key>.csv (the first one is profile.csv).
  for (std::size_t q = 1; q < o.profiles.size(); ++q)
    io::write_text_file(d / ("profile_" + fit_file_stem(spec.parameters[o.profiles[q].parameter].key) + ".csv"),
                        profile_csv(o.profiles[q].points));
  for (const auto& r : o.best_runs) {
    const std::string stem = "AQ_" + fit_file_stem(spec.experiments[r.experiment].name);
    io::write_text_file(d / (stem + "_model.csv"), two_columns("Q_N,A_m2", r.loading.size(), [&](std::size_t k) {
                          return std::pair{r.loading[k].Q, r.loading[k].A};
                        }));
    if (r.measured)
      io::write_text_file(d / (stem + "_measured.csv"),
                          two_columns("Q_N,A_m2", r.measured->Q_N.size(), [&](std::size_t k) {
                            return std::pair{r.measured->Q_N[k], r.measured->A_m2[k]};
                          }));
    if (r.force) {  // area_and_force: the model's Q(t) at the fit and the measured Q(t)
      const std::string qstem = "Qt_" + fit_file_stem(spec.experiments[r.experiment].name);
      io::write_text_file(d / (qstem + "_model.csv"), two_columns("t_s,Q_N", r.series.size(), [&](std::size_t k) {
                            return std::pair{r.series[k].t, r.series[k].Q};
                          }));
      io::write_text_file(d / (qstem + "_measured.csv"),
                          two_columns("t_s,Q_N", r.force->t_s.size(), [&](std::size_t k) {
                            return std::pair{r.force->t_s[k], r.force->Q_N[k]};
                          }));
    }
  }
}

// Writes the files of one optimization into `d` (plots when `plots`).
void write_optimization(const fs::path& d, const FitSpec& spec, const Optimization& o, bool plots,
                        const FigureFormats& figures) {
  fs::create_directories(d);
  write_optimization_tables(d, spec, o);
  if (!plots) return;
  bool stand_in = false;
  for (const auto& r : o.best_runs) stand_in = stand_in || r.stand_in;
  // The figures of every chosen format, each format's terminal before its figures.
  std::string script;
  for (const fs::path& probe : figure_files("convergence.png", figures)) {
    const std::string ext = probe.extension().string();
    const std::string gp =
        "set datafile separator ','\nset grid\n" + stand_in_mark(stand_in) + optimization_figures(spec, o, ext);
    script += terminal_for(probe, kFitPlotWidth, kFitPlotHeight) + "\n" + script_for_terminal(probe, gp);
  }
  plot_quietly(d, script, "plots.gp");
}

// fitted.png's key, drawn by hand above the plot (the fitted values may fill any corner):
// gnuplot's key sample of yerrorbars is a horizontal bar, the figure's are vertical. A vertical
// bar with caps and its point, then the text.
constexpr const char* kErrorBarKey =
    "set tmargin 5.5\nset title offset 0, 1.8\n"
    "set arrow 98 from graph 0.03, graph 1.01 to graph 0.03, graph 1.10 heads size screen 0.006,90 nofilled "
    "lc rgb '#1f4e9a' lw 1\n"
    "set label 97 '' at graph 0.03, graph 1.055 point pt 7 lc rgb '#1f4e9a'\n"
    "set label 96 'fit (bars: error-bar range)' at graph 0.06, graph 1.055 left\n";

constexpr const char* kFitHeader = "# asperity fit results (SI units: m, m², N, s; alpha_b in m^(2p+2)/N²)";

// The observables of each best run in fit.yaml, in this order.
const char* const kFitYamlObservables[] = {"alpha",
                                           "alpha_measured",
                                           "alpha_R2",
                                           "shape_exponent",
                                           "shape_exponent_measured",
                                           "A0",
                                           "Q_s",
                                           "A_s",
                                           "t_peak",
                                           "area_drop_fraction",
                                           "ss_cycles",
                                           "ss_drop",
                                           "ss_period"};

// The parametric bootstrap's spread (FitSpec::bootstrap_draws), beside the Hessian's σ.
void write_bootstrap(std::ostream& y, const Optimization& o, std::uint64_t seed) {
  const Bootstrap& bs = o.bootstrap;
  y << "      bootstrap:\n";
  y << "        method: \"parametric: synthetic data sets, the model's A(Q) and Q(t) at the optimum plus Gaussian "
       "noise at the fit's noise levels times s (the root of the reduced chi-square, as the Hessian's covariance), "
       "each refitted by the local stage from the optimum; sigma: standard "
       "deviation of their optima; interval95: value +- 1.96 sigma; hessian_ratio: sigma over the Hessian's "
       "sigma\"\n";
  y << "        draws: " << bs.draws.size() << "\n        succeeded: " << bs.succeeded << "\n        seed: " << seed
    << "\n        evaluations: " << bs.evaluations << "\n        wall_s: " << yaml_double(bs.wall_s) << "\n";
  if (!bs.failure.empty()) {
    y << "        failure: " << io::yaml_quoted(bs.failure) << "\n";
    return;
  }
  const Uncertainty& un = o.uncertainty;
  y << "        parameters:\n";
  for (std::size_t i = 0; i < o.variables.size(); ++i) {
    const double x = o.best[i], sg = bs.sigma[i];
    const double ratio = un.computed ? sg / un.sigma[i] : Observables::nan;
    y << "          " << io::yaml_quoted(o.variables[i].label) << ": {value: " << yaml_double(x)
      << ", sigma: " << yaml_double(sg) << ", sigma_relative: " << yaml_double(sg / std::abs(x)) << ", interval95: ["
      << yaml_double(x - 1.96 * sg) << ", " << yaml_double(x + 1.96 * sg) << "], mean: " << yaml_double(bs.mean[i])
      << ", hessian_ratio: " << yaml_double(ratio) << "}\n";
  }
  y << "        optima:   # per draw: objective, then the free variables in the order above\n";
  for (const BootstrapDraw& bd : bs.draws) {
    y << "          - [" << yaml_double(bd.objective);
    for (const double v : bd.best) y << ", " << yaml_double(v);
    y << "]\n";
  }
}

// The fit's statistical uncertainty (area_and_force with intervals): method, s², σ, intervals, correlation.
void write_uncertainty(std::ostream& y, const Optimization& o, std::uint64_t seed) {
  const Uncertainty& un = o.uncertainty;
  y << "    uncertainty:\n";
  if (!o.certified()) {  // no numbers around a point no second start confirms as the minimum
    y << "      certified: false\n      failure: " << io::yaml_quoted(un.failure) << "\n";
    return;
  }
  y << "      certified: true\n";
  y << "      method: \"chi-square: Hessian H of the objective at the optimum by central differences (relative steps "
       "from "
    << yaml_double(un.step)
    << ", rescaled until each parameter's own rise is 1-16 s^2), covariance 2 s^2 H^-1, s^2 = objective / (residuals - "
       "free variables) (the reduced chi-square); "
       "sigma: marginal standard deviation; interval95: value +- 1.96 sigma; profile_interval: where the one-parameter "
       "profile (others at the optimum) rises by s^2 (conditional, narrower when correlated); profile_sigma: "
       "sqrt(s^2/c) "
       "of the least-squares parabola through the profile's points (conditional; robust to jumps of the objective "
       "below the points' spacing, where sigma is not)\"\n";
  y << "      residuals: " << un.residuals << "\n      reduced_chi2: " << yaml_double(un.reduced_chi2) << "\n";
  y << "      evaluations: " << un.evaluations << "\n      wall_s: " << yaml_double(un.wall_s) << "\n";
  if (!un.computed) {
    y << "      failure: " << io::yaml_quoted(un.failure) << "\n";
  } else {
    y << "      parameters:\n";
    for (std::size_t i = 0; i < o.variables.size(); ++i) {
      const double x = o.best[i], sg = un.sigma[i];
      double plo = Observables::nan, phi = Observables::nan, psg = Observables::nan;
      for (const ParameterProfile& pp : o.profiles)
        if (pp.parameter == o.variables[i].parameter && o.variables[i].experiment < 0)
          plo = pp.lo, phi = pp.hi, psg = pp.parabola_sigma;
      y << "        " << io::yaml_quoted(o.variables[i].label) << ": {value: " << yaml_double(x)
        << ", step: " << yaml_double(un.steps[i]) << ", sigma: " << yaml_double(sg)
        << ", sigma_relative: " << yaml_double(sg / std::abs(x)) << ", interval95: [" << yaml_double(x - 1.96 * sg)
        << ", " << yaml_double(x + 1.96 * sg) << "], profile_interval: [" << yaml_double(plo) << ", "
        << yaml_double(phi) << "], profile_sigma: " << yaml_double(psg) << "}\n";
    }
    y << "      correlation:\n";
    for (std::size_t i = 0; i < o.variables.size(); ++i) {
      y << "        - [";
      for (std::size_t j = 0; j < o.variables.size(); ++j) y << (j ? ", " : "") << yaml_double(un.correlation[i][j]);
      y << "]\n";
    }
  }
  if (!o.bootstrap.draws.empty() || !o.bootstrap.failure.empty()) write_bootstrap(y, o, seed);
}

// The starts of one optimization and the verdict on them (fit/convergence.hpp).
void write_convergence(std::ostream& y, const Optimization& o) {
  y << "    converged: " << converged_name(o.converged)
    << "   # yes: >= 2 starts in the best basin; no: only the best start; unverified: one start\n";
  y << "    convergence: " << io::yaml_quoted(o.convergence) << "\n";
  y << "    starts: " << o.starts.size() << "\n";
  y << "    best_start: " << o.best_start + 1 << "   # its stop_reason above\n";
  y << "    in_best_basin: " << o.in_best_basin << "\n";
  y << "    spread:   # of the optima of the starts in the best basin\n";
  y << "      scaled: " << yaml_double(o.spread) << "   # largest distance from the best, scaled coordinates\n";
  y << "      parameters:\n";
  for (std::size_t i = 0; i < o.variables.size(); ++i) {
    double lo = Observables::nan, hi = Observables::nan;
    for (const StartRun& s : o.starts)
      if (s.in_best_basin && i < s.best.size()) lo = std::fmin(lo, s.best[i]), hi = std::fmax(hi, s.best[i]);
    y << "        " << io::yaml_quoted(o.variables[i].label) << ": [" << yaml_double(lo) << ", " << yaml_double(hi)
      << "]\n";
  }
  y << "    start_runs:\n";
  for (std::size_t k = 0; k < o.starts.size(); ++k) {
    const StartRun& s = o.starts[k];
    y << "      - {start: " << k + 1 << ", from: [";
    for (std::size_t i = 0; i < s.from.size(); ++i) y << (i ? ", " : "") << yaml_double(s.from[i]);
    y << "], best: [";
    for (std::size_t i = 0; i < s.best.size(); ++i) y << (i ? ", " : "") << yaml_double(s.best[i]);
    y << "], objective: " << yaml_double(s.objective) << ", evaluations: " << s.evaluations
      << ", stop_reason: " << io::yaml_quoted(s.stop_reason)
      << ", in_best_basin: " << (s.in_best_basin ? "true" : "false");
    if (!s.failure.empty()) y << ", failure: " << io::yaml_quoted(s.failure);
    y << "}\n";
  }
}

// fit.yaml's settings: the header, the fit file, the algorithm and its stopping rules, wall times.
void write_fit_settings(std::ostream& y, const FitSpec& spec, const FitResult& result, bool stand_in) {
  y << "asperity_version: " << io::yaml_quoted(io::build_info().version) << "\n";
  y << "fit_file: " << io::yaml_quoted(io::result_path(spec.file)) << "\n";
  y << "name: " << io::yaml_quoted(spec.name) << "\n";
  y << "description: " << io::yaml_quoted(spec.description) << "\n";
  y << "data: " << (stand_in ? "stand-in" : "measured") << "\n";
  y << "objective: " << objective_name(spec.objective) << "\n";
  if (spec.objective == FitObjective::area_and_force)
    y << "force_score: " << force_score_name(spec.force_score) << "\n";
  y << "mode: " << (spec.separate ? "separate" : "joint") << "\n";
  y << "algorithm: " << spec.algorithm << "\n";
  if (!spec.polish_algorithm.empty())
    y << "polish: {algorithm: " << spec.polish_algorithm << ", max_evaluations: " << spec.polish_max_evaluations
      << "}\n";
  y << "xtol_rel: " << yaml_double(spec.xtol_rel) << "\nftol_rel: " << yaml_double(spec.ftol_rel)
    << "\nftol_abs: " << yaml_double(spec.ftol_abs) << "\n";
  y << "max_evaluations: " << spec.max_evaluations << "\ninitial_step: " << yaml_double(spec.initial_step) << "\n";
  y << "starts: " << spec.starts << "   # the algorithm from the start, then the local stage from Sobol points\n";
  y << "basin: {tolerance: " << yaml_double(spec.basin_tolerance) << ", distance: " << yaml_double(spec.basin_distance)
    << "}   # a start is in the best basin within this relative objective or scaled distance\n";
  y << "certify: " << (spec.certify ? "true" : "false")
    << "   # true: a fit no second start confirms is a failed check (exit 1)\n";
  y << "threads: " << result.threads << "\n";
  y << "wall_s: " << yaml_double(result.wall_s) << "   # everything: fits, re-runs, profiles, error-bar refits\n";
  y << "fit_wall_s: " << yaml_double(result.fit_wall_s) << "   # sum of the optimizations alone\n";
  int total = 0;
  for (const auto& o : result.fits) total += o.evaluations;
  y << "evaluations: " << total << "   # of the optimizations (without profiles and refits)\n";
}

// The best run of each experiment of one optimization.
void write_best_runs(std::ostream& y, const FitSpec& spec, const Optimization& o) {
  y << "    runs:   # the best run of each experiment\n";
  for (const auto& r : o.best_runs) {
    const Observables& b = r.obs;
    y << "      " << io::yaml_quoted(spec.experiments[r.experiment].name) << ":\n";
    y << "        stand_in: " << (r.stand_in ? "true" : "false") << "\n";
    y << "        mass: " << yaml_double(r.mass_kg) << "\n";
    y << "        term: " << yaml_double(r.residual) << "\n";
    if (spec.objective == FitObjective::area_and_force)
      y << "        chi2: {area: " << yaml_double(r.terms.area) << ", n_area: " << r.terms.n_area
        << ", force: " << yaml_double(r.terms.force) << ", n_force: " << r.terms.n_force
        << ", score: " << force_score_name(r.terms.score) << ", cycles: " << yaml_double(r.terms.cycles)
        << ", n_cycles: " << r.terms.n_cycles << ", stick_slip: " << yaml_double(r.terms.stick_slip)
        << ", n_stick_slip: " << r.terms.n_stick_slip << "}\n";
    for (const char* name : kFitYamlObservables) {
      const ObservableField& f = observable_field(name);
      y << "        " << f.name << ": " << observable_text(f, b, yaml_double) << "\n";
    }
    y << "        run_wall_s: " << yaml_double(b.wall_s) << "\n";
  }
}

// The objective profiles of one optimization (the first, then the further parameters).
void write_profiles(std::ostream& y, const FitSpec& spec, const Optimization& o) {
  if (!o.profile.empty()) {
    const ProfileSettings& ps = spec.profile_settings;
    double fmin = Observables::nan, fmin_at = Observables::nan;
    for (const auto& p : o.profile)
      if (std::isfinite(p.objective) && !(p.objective >= fmin)) fmin = p.objective, fmin_at = p.factor;
    y << "    profile:\n";
    y << "      parameter: " << spec.parameters[ps.parameter].key << "\n";
    y << "      span: " << yaml_double(ps.span) << "\n      points: " << o.profile.size() << "\n";
    const std::string sub = fit_subdir(spec, o);
    y << "      file: " << io::yaml_quoted(sub.empty() ? "profile.csv" : sub + "/profile.csv") << "\n";
    y << "      lowest_objective_at_factor: " << yaml_double(fmin_at) << "   # 1: the fit is the profile's minimum\n";
    y << "      wall_s: " << yaml_double(o.profile_wall_s) << "\n";
  }
  for (std::size_t q = 1; q < o.profiles.size(); ++q) {
    if (q == 1) y << "    more_profiles:   # the further profiled parameters (same span and points)\n";
    const std::string& key = spec.parameters[o.profiles[q].parameter].key;
    const std::string sub = fit_subdir(spec, o);
    const std::string file = "profile_" + fit_file_stem(key) + ".csv";
    y << "      - {parameter: " << key << ", file: " << io::yaml_quoted(sub.empty() ? file : sub + "/" + file) << "}\n";
  }
}

// The error-bar refits of one optimization and the ranges they give.
void write_error_bars(std::ostream& y, const Optimization& o) {
  if (o.refits.empty()) return;
  y << "    error_bars:\n";
  y << "      method: \"one at a time: refit (from the optimum) with each quantity at nominal - bar and nominal + "
       "bar, "
       "the others nominal; min/max over the fit and all refits; sigma = quadrature sum over quantities of "
       "|x(+bar) - x(-bar)|/2 (linear propagation of independent errors)\"\n";
  y << "      wall_s: " << yaml_double(o.refits_wall_s) << "\n";
  y << "      refits:\n";
  for (const auto& rf : o.refits) {
    y << "        - {key: " << rf.key << ", shift: " << yaml_double(rf.sign * rf.bar);
    for (std::size_t i = 0; i < o.variables.size(); ++i)
      y << ", " << io::yaml_quoted(o.variables[i].label) << ": " << yaml_double(rf.best[i]);
    y << ", objective: " << yaml_double(rf.objective) << ", evaluations: " << rf.evaluations
      << ", stop_reason: " << rf.stop_reason;
    if (!rf.failure.empty()) y << ", failure: " << io::yaml_quoted(rf.failure);
    y << "}\n";
  }
  const std::vector<Range> ranges = error_bar_ranges(o);
  y << "      ranges:\n";
  for (std::size_t i = 0; i < ranges.size(); ++i)
    y << "        " << io::yaml_quoted(o.variables[i].label) << ": {value: " << yaml_double(ranges[i].value)
      << ", min: " << yaml_double(ranges[i].min) << ", max: " << yaml_double(ranges[i].max)
      << ", sigma: " << yaml_double(ranges[i].sigma)
      << ", sigma_relative: " << yaml_double(ranges[i].sigma / std::abs(ranges[i].value)) << "}\n";
}

}  // namespace

std::string fit_yaml(const FitSpec& spec, const FitResult& result, const std::string& command_line) {
  std::ostringstream y;
  bool stand_in = false;
  for (const auto& o : result.fits)
    for (const auto& r : o.best_runs) stand_in = stand_in || r.stand_in;
  y << kFitHeader << "\n";
  if (stand_in)
    y << "# STAND-IN DATA: the experiments fitted here are stand-ins generated by `asperity generate`,\n"
         "# not measurements. The fitted values are properties of the stand-ins, not of the real experiments.\n";
  write_fit_settings(y, spec, result, stand_in);
  y << "fits:\n";
  for (const auto& o : result.fits) {
    y << "  - label: " << io::yaml_quoted(o.label) << "\n";
    y << "    files: " << io::yaml_quoted(fit_subdir(spec, o).empty() ? "." : fit_subdir(spec, o)) << "\n";
    y << "    experiments: [";
    for (std::size_t k = 0; k < o.experiments.size(); ++k)
      y << (k ? ", " : "") << io::yaml_quoted(spec.experiments[o.experiments[k]].name);
    y << "]\n";
    y << "    status: " << (o.ok() ? "ok" : "failed") << "\n";
    if (!o.ok()) y << "    failure: " << io::yaml_quoted(o.failure) << "\n";
    y << "    stop_reason: " << o.stop_reason << "   # NLopt result\n";
    write_convergence(y, o);
    y << "    evaluations: " << o.evaluations << "\n";
    y << "    wall_s: " << yaml_double(o.wall_s) << "\n";
    y << "    objective: " << yaml_double(o.objective) << "\n";
    y << "    parameters:\n";
    for (std::size_t i = 0; i < o.variables.size(); ++i) {
      const FitParameter& p = spec.parameters[o.variables[i].parameter];
      y << "      " << io::yaml_quoted(o.variables[i].label) << ": {value: " << yaml_double(o.best[i])
        << ", start: " << yaml_double(o.start[i]) << ", lo: " << yaml_double(p.lo) << ", hi: " << yaml_double(p.hi)
        << ", scale: " << (p.log_scale ? "log" : "linear");
      const bool at_bound = o.best[i] == p.lo || o.best[i] == p.hi;
      y << ", at_bound: " << (at_bound ? "true" : "false") << "}\n";
    }
    write_best_runs(y, spec, o);
    write_profiles(y, spec, o);
    if (spec.objective == FitObjective::area_and_force && spec.intervals) write_uncertainty(y, o, spec.bootstrap_seed);
    write_error_bars(y, o);
  }
  // Provenance: the build, the command, and the fit file and every experiment's input files.
  std::vector<io::DataFile> files{{"fit", spec.file}};
  for (const FitExperiment& e : spec.experiments) {
    const std::vector<io::DataFile> f = input_files(e.scene.build());
    files.insert(files.end(), f.begin(), f.end());
  }
  y << io::provenance_yaml(command_line, files);
  return y.str();
}

void check_fit_dir(const fs::path& dir) { check_publishable(dir, "fit", "--out"); }  // names the folder as given

void claim_fit_dir(const fs::path& dir) {
  check_fit_dir(dir);
  claim_dir(dir, "fit", "--out", {}, true);  // a marker listing the results publish_dir will write
}

// The observables of fitted.csv: (column, observable_fields() name).
const std::pair<const char*, const char*> kFittedObservables[] = {
    {"alpha", "alpha"},
    {"alpha_measured", "alpha_measured"},
    {"Q_s_N", "Q_s"},
    {"area_drop_fraction", "area_drop_fraction"},
    {"shape_exponent", "shape_exponent"},
    {"shape_exponent_measured", "shape_exponent_measured"}};

void write_fit(const fs::path& dir, const FitSpec& spec, const FitResult& result, const std::string& command_line,
               const FigureFormats& figures) {
  // The results go in beside the fit's journals (journal.csv, inputs.txt, tasks/), which stay
  // where they are: publish_dir replaces only the result files the last write listed.
  publish_dir(dir, "fit", "--out", [&](const fs::path& tmp) {
    const bool plots = io::gnuplot_available();
    for (const auto& o : result.fits) write_optimization(tmp / fit_subdir(spec, o), spec, o, plots, figures);

    // fitted.csv: one row per (optimization, experiment).
    std::ostringstream c;
    c << "fit,experiment,stand_in,mass_kg,P_N";
    for (const auto& p : spec.parameters)
      c << "," << io::csv_field(p.key) << "," << io::csv_field(p.key + "_min") << "," << io::csv_field(p.key + "_max");
    c << ",objective,term";
    for (const auto& [column, field] : kFittedObservables) c << "," << column;
    c << ",evaluations,wall_s,stop_reason,status\n";
    std::vector<std::vector<double>> first;  // (P, value, low, high) of the first parameter, for fitted.png
    for (const auto& o : result.fits) {
      const std::vector<Range> ranges = error_bar_ranges(o);
      for (const auto& r : o.best_runs) {
        c << io::csv_field(o.label) << "," << io::csv_field(spec.experiments[r.experiment].name) << ","
          << (r.stand_in ? "true" : "false") << "," << format_g17(r.mass_kg) << "," << format_g17(r.mass_kg * kGravity);
        for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
          Range v;
          for (std::size_t i = 0; i < o.variables.size(); ++i)
            if (o.variables[i].parameter == j &&
                (o.variables[i].experiment < 0 || static_cast<std::size_t>(o.variables[i].experiment) == r.experiment))
              v = o.refits.empty() ? Range{o.best[i], Observables::nan, Observables::nan, Observables::nan} : ranges[i];
          c << "," << format_g17(v.value) << "," << format_g17(v.min) << "," << format_g17(v.max);
          if (j == 0)
            first.push_back({r.mass_kg * kGravity, v.value, std::isnan(v.min) ? v.value : v.min,
                             std::isnan(v.max) ? v.value : v.max});
        }
        c << "," << format_g17(o.objective) << "," << format_g17(r.residual);
        for (const auto& [column, field] : kFittedObservables)
          c << "," << format_g17(observable_field(field).value(r.obs));
        c << "," << o.evaluations << "," << format_g17(o.wall_s) << "," << io::csv_field(o.stop_reason) << ","
          << (o.ok() ? "ok" : "failed") << "\n";
      }
    }
    io::write_text_file(tmp / "fitted.csv", c.str());
    if (plots && spec.separate && result.fits.size() > 1) {
      // First parameter against the load, with the error-bar range when computed.
      // The numbers travel in a data block: fitted.csv's quoted names may hold commas.
      std::string script = gnuplot_block("fitted", first);
      std::vector<double> values;  // of the y axis: values and bar ends
      for (const auto& row : first) values.insert(values.end(), row.begin() + 1, row.end());
      bool stand_in = false;
      for (const auto& o : result.fits)
        for (const auto& r : o.best_runs) stand_in = stand_in || r.stand_in;
      for (const fs::path& probe : figure_files("fitted.png", figures)) {
        std::ostringstream gp;
        gp << "set grid\nset output " << gnuplot_quote(probe.string()) << "\n"
           << stand_in_mark(stand_in) << "set title " << title_lines(spec.name, kColumnTitleChars - 26) << " . "
           << gnuplot_quote(": fitted " + column_symbol(spec.parameters[0].key) + " per experiment")
           << "\nset xlabel 'P = M g [N]'\nset ylabel " << gnuplot_quote(axis_markup(spec.parameters[0].key)) << "\n"
           << kErrorBarKey << tic_format("y", values)
           << "plot $fitted using 1:2:3:4 with yerrorbars pt 7 lc rgb '#1f4e9a' notitle\n";
        script += terminal_for(probe, kFitPlotWidth, kFitPlotHeight) + "\n" + script_for_terminal(probe, gp.str());
      }
      plot_quietly(tmp, script, "fitted.gp");
    }
    io::write_text_file(tmp / "fit.yaml", fit_yaml(spec, result, command_line));
  });
}

}  // namespace asperity
