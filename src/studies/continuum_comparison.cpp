#include "studies/continuum_comparison.hpp"
#include "studies/study_file.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "scene/topography_junctions.hpp"
#include "scene/topography_recipe_load.hpp"
#include "solve/quasi_static/junction_curve.hpp"
#include "studies/continuum_rule.hpp"
#include "surface/tangential_contact.hpp"

namespace asperity {
namespace fs = std::filesystem;
namespace {

constexpr const char* kSynthetic = "SYNTHETIC surface";

struct Curve {
  std::string model;
  std::vector<double> delta, force, slip;  // from δ = 0
  double k0 = 0, full_force = 0, full_delta = 0;
  bool converged = true, monotone = true;
};

// Q / Q_full where the slipping area first reaches `fraction` (linear between the points).
double force_at_slip(const Curve& c, double fraction) {
  for (std::size_t i = 1; i < c.slip.size(); ++i)
    if (c.slip[i] >= fraction) {
      const double s0 = c.slip[i - 1], s1 = c.slip[i];
      const double w = s1 > s0 ? (fraction - s0) / (s1 - s0) : 1.0;
      return (c.force[i - 1] + w * (c.force[i] - c.force[i - 1])) / c.full_force;
    }
  return std::nan("");
}

Curve continuum_curve(TangentialContact& t, const std::vector<double>& deltas) {
  Curve c;
  c.model = "continuum";
  c.k0 = t.initial_stiffness_N_per_m();
  c.full_force = t.full_sliding_force_N();
  c.full_delta = t.full_sliding_displacement_m();
  c.delta = {0}, c.force = {0}, c.slip = {0};
  std::vector<double> before;
  for (const double d : deltas) {
    if (d >= c.full_delta) {  // every pixel at its bound from there on
      c.delta.push_back(d), c.force.push_back(c.full_force), c.slip.push_back(1.0);
      continue;
    }
    const TangentialState st = t.solve(d);
    c.converged = c.converged && st.converged;
    c.delta.push_back(d), c.force.push_back(st.force_N);
    c.slip.push_back(static_cast<double>(st.slipping_pixels) /
                     static_cast<double>(std::max<std::size_t>(1, st.contact_pixels)));
  }
  return c;
}

Curve junction_curve(const JunctionPopulation& J, double E, double sigma, bool interacting, TractionWeighting w,
                     const std::string& model, const std::vector<double>& deltas, double tolerance) {
  QuasiStaticJunctions q;
  q.area_m2 = J.area_m2, q.x_m = J.x_m, q.y_m = J.y_m;
  q.E_Pa = E, q.nu = 0.5, q.shear_strength_Pa = sigma, q.interacting = interacting, q.weighting = w;
  q.tolerance = tolerance;
  const JunctionCurve jc = quasi_static_junction_curve(q, deltas);
  Curve c;
  c.model = model;
  c.k0 = jc.initial_stiffness_N_per_m, c.full_force = jc.full_sliding_force_N,
  c.full_delta = jc.full_sliding_displacement_m;
  c.monotone = jc.monotone;
  c.delta = {0}, c.force = {0}, c.slip = {0};
  for (const JunctionCurvePoint& p : jc.points) {
    c.delta.push_back(p.displacement_m), c.force.push_back(p.force_N), c.slip.push_back(p.slip_area_fraction);
    c.converged = c.converged && p.converged;
  }
  return c;
}

void write_files(const ContinuumStudyOptions& o, const ContinuumStudy& s, const std::string& recipe_text);

}  // namespace

ContinuumStudy run_continuum_study(const ContinuumStudyOptions& o) {
  if (o.points < 2 || o.points > 10000) throw std::invalid_argument("study continuum: points must be in [2, 10000]");
  TopographyRecipe recipe = load_topography_recipe(o.recipe);
  if (recipe.nu != 0.5)
    throw io::InputError(o.recipe.string(), 0, "nu", "the continuum reference solves nu = 0.5 only (the paper's PDMS)");
  const double E = recipe.E_Pa, sigma = recipe.sigma_exp;  // ε = 1: σ = σ_exp
  ContinuumStudy study;
  for (const double P : o.loads_N) {
    recipe.load_N = P;
    NormalContact normal;
    const TopographyContact tc = solve_topography_contact(recipe, o.threads, &normal);
    const double Es = E / (1 - recipe.nu * recipe.nu);
    const double aH = std::cbrt(3 * P * recipe.sphere_radius_m / (4 * Es));
    TangentialContactSettings ts;
    ts.E_Pa = E;
    ts.nu = 0.5;
    ts.tolerance = o.tolerance;
    ts.threads = o.threads;
    TangentialContact continuum(tc.n, tc.pixel_m, shear_strength_bound(normal, sigma), ts);
    // The displacements: up to 1.25 × the continuum's full sliding.
    const double cont_full = continuum.full_sliding_displacement_m();
    std::vector<double> deltas;
    for (int i = 1; i <= o.points; ++i) deltas.push_back(1.25 * cont_full * i / o.points);
    if (o.log)
      *o.log << "  " << P << " N: " << tc.junctions.size() << " junctions, contact " << tc.contact_area_m2 * 1e6
             << " mm^2" << std::flush;
    std::vector<Curve> curves;
    curves.push_back(continuum_curve(continuum, deltas));
    curves.push_back(
        junction_curve(tc.junctions, E, sigma, false, TractionWeighting::uniform, "independent", deltas, o.tolerance));
    curves.push_back(junction_curve(tc.junctions, E, sigma, true, TractionWeighting::uniform, "interacting-uniform",
                                    deltas, o.tolerance));
    curves.push_back(junction_curve(tc.junctions, E, sigma, true, TractionWeighting::rigid, "interacting-rigid", deltas,
                                    o.tolerance));
    const Curve& ref = curves[0];
    for (const Curve& c : curves) {
      ContinuumRow r;
      r.load_N = P;
      r.junctions = tc.junctions.size();
      r.contact_area_m2 = tc.contact_area_m2;
      r.pixels_per_junction = tc.contact_area_m2 / (tc.pixel_m * tc.pixel_m) / static_cast<double>(tc.junctions.size());
      r.coverage_hertz = tc.contact_area_m2 / (std::numbers::pi * aH * aH);
      const PopulationMeasures pm = population_measures(tc.junctions.area_m2, tc.junctions.x_m, tc.junctions.y_m);
      r.coverage_population = pm.coverage, r.stiffness_ratio = pm.stiffness_ratio;
      r.model = c.model;
      r.initial_stiffness_N_per_m = c.k0;
      r.stiffness_error = c.k0 / ref.k0 - 1;
      r.q10 = force_at_slip(c, 0.1), r.q50 = force_at_slip(c, 0.5);
      r.full_sliding_displacement_m = c.full_delta;
      r.full_sliding_error = c.full_delta / ref.full_delta - 1;
      double ss = 0;
      for (std::size_t i = 1; i < c.force.size(); ++i) ss += std::pow((c.force[i] - ref.force[i]) / ref.full_force, 2);
      r.rms_error = std::sqrt(ss / static_cast<double>(c.force.size() - 1));
      r.converged = c.converged, r.monotone = c.monotone;
      study.rows.push_back(r);
      for (std::size_t i = 0; i < c.delta.size(); ++i)
        study.curves.push_back({P, c.model, c.delta[i], c.force[i], c.slip[i]});
    }
    if (o.log)
      *o.log << ", coverage " << study.rows.back().coverage_population << ", stiffness ratio "
             << study.rows.back().stiffness_ratio << ": stiffness error independent "
             << 100 * study.rows[study.rows.size() - 3].stiffness_error << " %, interacting (rigid) "
             << 100 * study.rows.back().stiffness_error << " %" << std::endl;
  }
  write_files(o, study, topography_section_yaml(recipe, false));
  return study;
}

namespace {

std::string fixed(double v, int digits) { return io::format_cell(("%." + std::to_string(digits) + "f").c_str(), v); }

std::string plot_script(const ContinuumStudy& s, const std::optional<StiffnessRule>& rule) {
  std::ostringstream gp;
  const char* models[] = {"independent", "interacting-uniform", "interacting-rigid"};
  for (int m = 0; m < 3; ++m) {
    std::vector<std::vector<double>> rows;
    for (const ContinuumRow& r : s.rows)
      if (r.model == models[m])
        rows.push_back({r.stiffness_ratio, 100 * std::abs(r.stiffness_error), 100 * r.rms_error});
    gp << gnuplot_block("m" + std::to_string(m), rows);
  }
  double heaviest = 0;
  for (const ContinuumRow& r : s.rows) heaviest = std::max(heaviest, r.load_N);
  double ref_full = 1, ref_force = 1;
  for (const ContinuumRow& r : s.rows)
    if (r.load_N == heaviest && r.model == "continuum") ref_full = r.full_sliding_displacement_m;
  const char* all[] = {"continuum", "independent", "interacting-uniform", "interacting-rigid"};
  for (int m = 0; m < 4; ++m) {
    std::vector<std::vector<double>> rows;
    for (const ContinuumCurvePoint& p : s.curves)
      if (p.load_N == heaviest && p.model == all[m]) rows.push_back({p.displacement_m / ref_full, p.force_N});
    if (m == 0 && !rows.empty()) ref_force = rows.back()[1];
    for (auto& r : rows) r[1] /= ref_force;
    gp << gnuplot_block("c" + std::to_string(m), rows);
  }
  gp << "set multiplot layout 1,2 title "
     << gnuplot_quote(std::string(kSynthetic) +
                      "s: junction models against the continuum on the same contact map (α_b = 0, ε = 1)")
     << "\n";
  double lo = 0, hi = 0;
  for (const ContinuumRow& r : s.rows)
    lo = lo > 0 ? std::min(lo, r.stiffness_ratio) : r.stiffness_ratio, hi = std::max(hi, r.stiffness_ratio);
  gp << "set logscale xy\nset xrange [" << 0.8 * lo << ":" << 1.25 * hi
     << "]\nset xtics (1, 2, 5, 10, 20, 50)\nset xlabel " << gnuplot_quote("stiffness ratio Σ a_i / (√2 R_g) [1]")
     << "\nset ylabel " << gnuplot_quote("|error| [%]") << "\nset key top left\nset title "
     << gnuplot_quote("initial stiffness (points), rms of Q(δ)/Q_{full} (open)") << "\n";
  gp << "plot $m0 using 1:2 with points pt 7 lc rgb '#d55e00' title " << gnuplot_quote("independent")
     << ", $m1 using 1:2 with points pt 5 lc rgb '#009e73' title " << gnuplot_quote("interacting, uniform")
     << ", $m2 using 1:2 with points pt 9 lc rgb '#0072b2' title " << gnuplot_quote("interacting, rigid")
     << ", $m0 using 1:3 with points pt 6 lc rgb '#d55e00' notitle, $m1 using 1:3 with points pt 4 lc rgb '#009e73' "
        "notitle"
     << ", $m2 using 1:3 with points pt 8 lc rgb '#0072b2' notitle";
  if (rule)
    gp << ", [" << rule->ratio_min << ":" << rule->ratio_max << "] 100*" << rule->prefactor << "*x**" << rule->exponent
       << " with lines dt 2 lc rgb '#d55e00' title " << gnuplot_quote("rule (independent)");
  gp << "\nunset logscale\nset autoscale x\nset xtics autofreq\nset xlabel "
     << gnuplot_quote("δ / δ_{full} of the continuum [1]") << "\nset ylabel " << gnuplot_quote("Q / Q_{full} [1]")
     << "\nset key bottom right\nset title " << gnuplot_quote("Q(δ) at " + fixed(heaviest, 2) + " N")
     << "\nset yrange [0:1.05]\n";
  gp << "plot $c0 using 1:2 with lines lw 3 lc rgb 'black' title " << gnuplot_quote("continuum (FFT boundary elements)")
     << ", $c1 using 1:2 with lines lw 2 lc rgb '#d55e00' title " << gnuplot_quote("independent")
     << ", $c2 using 1:2 with lines lw 2 lc rgb '#009e73' title " << gnuplot_quote("interacting, uniform")
     << ", $c3 using 1:2 with lines lw 2 dt 2 lc rgb '#0072b2' title " << gnuplot_quote("interacting, rigid")
     << "\nunset multiplot\n";
  return gp.str();
}

void write_files(const ContinuumStudyOptions& o, const ContinuumStudy& s, const std::string& recipe_text) {
  fs::create_directories(o.out);
  std::ostringstream t;
  t << "# " << kSynthetic << " (" << o.recipe.filename().string() << "): `" << study_command(o.study_file) << "`\n"
    << "load_N,junctions,contact_area_m2,pixels_per_junction,coverage_hertz,coverage_population,stiffness_ratio,model,"
       "initial_stiffness_N_per_m,"
       "stiffness_error,q10_over_qfull,q50_over_qfull,full_sliding_displacement_m,full_sliding_error,rms_error,"
       "converged,monotone\n";
  for (const ContinuumRow& r : s.rows)
    t << io::csv_number(r.load_N) << ',' << r.junctions << ',' << io::csv_number(r.contact_area_m2) << ','
      << io::csv_number(r.pixels_per_junction) << ',' << io::csv_number(r.coverage_hertz) << ','
      << io::csv_number(r.coverage_population) << ',' << io::csv_number(r.stiffness_ratio) << ',' << r.model << ','
      << io::csv_number(r.initial_stiffness_N_per_m) << ',' << io::csv_number(r.stiffness_error) << ','
      << io::csv_number(r.q10) << ',' << io::csv_number(r.q50) << ',' << io::csv_number(r.full_sliding_displacement_m)
      << ',' << io::csv_number(r.full_sliding_error) << ',' << io::csv_number(r.rms_error) << ','
      << (r.converged ? "true" : "false") << ',' << (r.monotone ? "true" : "false") << '\n';
  io::write_text_file(o.out / "table.csv", t.str());
  std::ostringstream c;
  c << "# " << kSynthetic << ": Q(delta) of each model, `" << study_command(o.study_file)
    << "`\nload_N,model,displacement_m,force_N,slip_area_fraction\n";
  for (const ContinuumCurvePoint& p : s.curves)
    c << io::csv_number(p.load_N) << ',' << p.model << ',' << io::csv_number(p.displacement_m) << ','
      << io::csv_number(p.force_N) << ',' << io::csv_number(p.slip_area_fraction) << '\n';
  io::write_text_file(o.out / "curves.csv", c.str());

  std::vector<double> cov, err;
  for (const ContinuumRow& r : s.rows)
    if (r.model == "independent") cov.push_back(r.stiffness_ratio), err.push_back(std::abs(r.stiffness_error));
  const std::optional<StiffnessRule> rule = fit_stiffness_rule(cov, err);
  std::ostringstream rl;
  rl << "# " << kSynthetic << ": |stiffness error of independent junctions| = prefactor * stiffness_ratio^exponent, `"
     << study_command(o.study_file) << "`\n"
     << "prefactor,exponent,ratio_min,ratio_max,points\n";
  if (rule)
    rl << io::csv_number(rule->prefactor) << ',' << io::csv_number(rule->exponent) << ','
       << io::csv_number(rule->ratio_min) << ',' << io::csv_number(rule->ratio_max) << ',' << rule->points << '\n';
  io::write_text_file(o.out / "rule.csv", rl.str());

  std::ostringstream md;
  md << "# Junction models against the continuum\n\n**" << kSynthetic
     << ".** The surface is a seeded self-affine one, not a measured topography. Made by `"
     << study_command(o.study_file) << "` (docs/continuum.md) from this recipe, at each load of the table:\n\n```yaml\n"
     << recipe_text << "```\n\n"
     << "The continuum is the tangential contact on the normal solve's contact map (FFT boundary elements, constant "
        "shear strength σ = σ_exp per unit area); the junction models take the junctions the same map makes, with "
        "α_b = 0 and ε = 1, quasi-statically. Errors are relative to the continuum.\n\n"
     << "| load [N] | junctions | pixels per junction | coverage (population) | coverage (Hertz) | stiffness ratio | "
        "model | k0 [N/m] | k0 error | Q10/Qfull | "
        "Q50/Qfull | δ_full error | rms of Q(δ)/Qfull |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ContinuumRow& r : s.rows)
    md << "| " << fixed(r.load_N, 2) << " | " << r.junctions << " | " << fixed(r.pixels_per_junction, 1) << " | "
       << fixed(r.coverage_population, 3) << " | " << fixed(r.coverage_hertz, 3) << " | " << fixed(r.stiffness_ratio, 2)
       << " | " << r.model << (r.converged ? "" : " (NOT converged)")
       << (r.monotone ? "" : " (a slip stopped between two points)") << " | "
       << io::format_cell("%.4g", r.initial_stiffness_N_per_m) << " | " << fixed(100 * r.stiffness_error, 1) << " % | "
       << fixed(r.q10, 3) << " | " << fixed(r.q50, 3) << " | " << fixed(100 * r.full_sliding_error, 1) << " % | "
       << fixed(100 * r.rms_error, 2) << " % |\n";
  md << "\n## The rule\n\n";
  if (rule) {
    md << "|k0 error of independent junctions| = " << io::format_cell("%.4g", rule->prefactor)
       << " · (stiffness ratio)^" << io::format_cell("%.3g", rule->exponent) << ", fitted over stiffness ratios "
       << fixed(rule->ratio_min, 2) << " to " << fixed(rule->ratio_max, 2) << " (" << rule->points
       << " loads; `rule.csv`). It reaches\n\n";
    for (const double e : {0.01, 0.05, 0.2}) {
      const double c = rule->ratio_for(e);
      md << "- " << fixed(100 * e, 0) << " % at stiffness ratio " << io::format_cell("%.3g", c)
         << (c < rule->ratio_min || c > rule->ratio_max ? " (extrapolated: outside the ratios measured)" : "") << "\n";
    }
  } else {
    md << "No evidence: fewer than two loads with a positive error.\n";
  }
  std::string error;
  if (!render_figures(o.out / "continuum.png", plot_script(s, rule), 1600, 700, o.figures, &error))
    md << "\ncontinuum.png not drawn: " << error << "\n";
  else
    md << "\n![errors against coverage; Q(δ) at the heaviest load](continuum.png)\n";
  io::write_text_file(o.out / "REPORT.md", md.str());
}

}  // namespace

}  // namespace asperity
