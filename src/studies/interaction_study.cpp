#include "studies/interaction_study.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include "fit/fit_load.hpp"
#include "fit/objective.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "observe/shape_comparison.hpp"
#include "observe/simulate.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"
#include "solve/interacting/interaction_matrix.hpp"
#include "studies/claims.hpp"
#include "studies/interaction_report.hpp"
#include "studies/interaction_verdicts.hpp"
#include "studies/joint_comparison.hpp"
#include "studies/junction_pairs.hpp"

namespace asperity {
namespace fs = std::filesystem;

using namespace interaction_detail;

namespace {

// label → best α_b of a fit.yaml written by `asperity fit` (separate fits); empty when absent.
std::map<std::string, double> calibrated_alpha_b(const fs::path& fit_yaml) {
  std::map<std::string, double> out;
  if (!fs::exists(fit_yaml)) return out;
  try {
    const YAML::Node root = io::load_yaml_file(fit_yaml, fit_yaml.string());  // the hardened reader
    for (const auto& f : root["fits"]) {
      if (f["status"].as<std::string>("") != "ok") continue;
      const YAML::Node p = f["parameters"]["model.alpha_b"];
      if (p && p["value"]) out[f["label"].as<std::string>()] = p["value"].as<double>();
    }
  } catch (const YAML::Exception& e) {  // not a fit.yaml of `asperity fit`
    throw io::InputError(fit_yaml.string(), e.mark.is_null() ? 0 : e.mark.line + 1, "fits", e.msg);
  }
  return out;
}

// Runs to five stick-slip cycles or `stop_time_s`.
Side run_side(const fs::path& scene_file, std::vector<std::string> set, std::optional<double> alpha_b,
              double stop_time_s) {
  Side s;
  if (!alpha_b) return s;
  set.push_back("model.alpha_b=" + io::csv_number(*alpha_b));
  set.push_back("stop.cycles=5");
  set.push_back("stop.time=" + io::csv_number(stop_time_s));
  const Scene scene = load_scene(scene_file, set);
  const RunResult r = simulate(scene);
  s.ran = true;
  s.alpha_b = *alpha_b;
  s.obs = r.obs;
  s.areas = compare_areas(scene, *alpha_b, r.obs, r.recorder.loading_branch());
  if (scene.experiment.measured) {
    const auto& a0 = scene.experiment.junctions.area_m2;
    s.shape = compare_shapes(r.recorder.loading_branch(), *scene.experiment.measured,
                             std::accumulate(a0.begin(), a0.end(), 0.0));
  }
  s.wall_s = r.obs.wall_s;
  return s;
}

// f_i/(σA_i) of every junction at half the first peak's time of `scene` (interacting) and at
// the peak; both empty when the run has no peak.
struct Ratios {
  std::vector<double> half, peak;
  double t_peak = NAN;
};
Ratios ratios_at_half_and_peak(const Scene& base) {
  Scene s = base;
  s.stop.at_first_peak = true;
  s.output.series.clear();
  const RunResult first = simulate(s);
  if (!first.obs.peak_found) return {};
  // Runs again to each time (the first run stops when the peak is confirmed, after it).
  s.stop.at_first_peak = false;
  auto at = [&](double t) {
    s.stop.time = t;
    const Problem p = make_problem(s);
    Recorder rec = make_recorder(s);
    InteractingEventStepper stepper(p);
    integrate(stepper, p, rec);
    return stepper.junctions().load_ratios(stepper.X());
  };
  return {at(0.5 * first.obs.t_peak), at(first.obs.t_peak), first.obs.t_peak};
}

Spread force_spread(const fs::path& scene_file, double alpha_b, const std::string& name) {
  Spread sp;
  sp.experiment = name;
  const Scene scene =
      load_scene(scene_file, {"model.interactions=elastic", "model.alpha_b=" + io::csv_number(alpha_b)});
  const auto& J = scene.experiment.junctions;
  const std::size_t n = J.size();
  sp.A0 = J.area_m2;
  sp.x = J.x_m;
  sp.y = J.y_m;
  // Crowding: the compliance the neighbours add at a junction, relative to its own, k_i Σ_j C_ij.
  const Problem p = make_problem(scene);
  const InteractionMatrix C = interaction_matrix(p);
  sp.crowding.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0;
    for (std::size_t j = 0; j < n; ++j) s += C(i, j);
    sp.crowding[i] = s * p.law.stiffness(J.area_m2[i], J.area_m2[i]);
  }
  Ratios inter = ratios_at_half_and_peak(scene);
  sp.ratio_inter = std::move(inter.peak);
  sp.half_inter = std::move(inter.half);
  sp.t_peak_inter = inter.t_peak;
  sp.inter = scene;
  // The independent model through the same code: the arrangement 10⁶ times wider (coupling
  // ~1e-6 of a junction's own compliance).
  Scene far = scene;
  far.model.position_scale = 1e6;
  Ratios indep = ratios_at_half_and_peak(far);
  sp.ratio_indep = std::move(indep.peak);
  sp.half_indep = std::move(indep.half);
  sp.t_peak_indep = indep.t_peak;
  sp.indep = far;
  for (const auto* v : {&sp.ratio_inter, &sp.ratio_indep, &sp.half_inter, &sp.half_indep})
    if (v->size() != n) return sp;
  // Equal areas: the stand-ins' cluster of large junctions (a lognormal of 2 % width).
  std::vector<double> sorted = J.area_m2;
  std::sort(sorted.begin(), sorted.end());
  const double top = sorted[sorted.size() - 1 - sorted.size() / 50];  // inside the top 4 %
  sp.area_lo = 0.95 * top;
  sp.area_hi = 1.05 * top;
  sp.equal.assign(n, 0);
  std::vector<double> cr;
  for (std::size_t i = 0; i < n; ++i)
    if (J.area_m2[i] >= sp.area_lo && J.area_m2[i] <= sp.area_hi) sp.equal[i] = 1, cr.push_back(sp.crowding[i]);
  std::sort(cr.begin(), cr.end());
  sp.crowding_median = cr.empty() ? NAN : cr[cr.size() / 2];
  sp.ran = cr.size() >= 6;
  return sp;
}

// Both models on every scene of the study; `spread_scene`: the scene of opt.spread_experiment.
std::vector<StudyRow> run_rows(const InteractionStudyOptions& opt, const std::map<std::string, double>& alpha_indep,
                               const std::map<std::string, double>& alpha_inter, fs::path& spread_scene) {
  std::vector<StudyRow> rows;
  for (const fs::path& f : opt.scenes) {
    const std::string name = load_scene(f).experiment.name;
    StudyRow r{name, {}, {}};
    auto find = [&](const std::map<std::string, double>& m) -> std::optional<double> {
      const auto it = m.find(name);
      return it == m.end() ? std::nullopt : std::optional<double>(it->second);
    };
    // Interactions delay the first peak about 1.8 times (P6.40N: 10.3 s), and the interacting
    // model glides after it (no cycles end its run early): 20 s for it, 12 s without.
    r.indep = run_side(f, {}, find(alpha_indep), 12.0);
    r.inter = run_side(f, {"model.interactions=elastic"}, find(alpha_inter), 20.0);
    if (opt.log)
      *opt.log << "  " << name << ": n independent " << io::format_cell("%.3f", r.indep.obs.shape_exponent)
               << ", interacting " << io::format_cell("%.3f", r.inter.obs.shape_exponent) << ", measured "
               << io::format_cell("%.3f", r.inter.areas.n_measured) << " (" << io::format_cell("%.1f", r.inter.wall_s)
               << " s)" << std::endl;
    if (name == opt.spread_experiment) spread_scene = f;
    rows.push_back(std::move(r));
  }
  return rows;
}

// Equal-area pairs, crowded vs sparse, in time (both models, to past the interacting peak): the
// section of REPORT.md that write_junction_pairs writes, and its files.
std::string write_pairs(const InteractionStudyOptions& opt, const Spread& sp) {
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < sp.A0.size(); ++i)
    if (sp.equal[i]) candidates.push_back(i);
  JunctionPairsEvidence ev;
  ev.experiment = sp.experiment;
  ev.stand_in = is_stand_in(sp.inter.experiment);
  ev.sigma_Pa = make_problem(sp.inter).law.sigma;  // σ of the threshold f = σA
  ev.t_peak_interacting_s = sp.t_peak_inter;
  ev.t_peak_independent_s = sp.t_peak_indep;
  ev.pairs = crowded_sparse_pairs(candidates, sp.crowding, 3);
  ev.A0_m2 = sp.A0;
  ev.crowding = sp.crowding;
  std::vector<std::size_t> tracked;
  for (const JunctionPair& pr : ev.pairs) tracked.push_back(pr.crowded), tracked.push_back(pr.sparse);
  const double t_end = 1.1 * std::max(sp.t_peak_inter, sp.t_peak_indep);
  ev.interacting = trace_junctions(sp.inter, tracked, t_end, 300);
  ev.independent = trace_junctions(sp.indep, tracked, t_end, 300);
  return write_junction_pairs(opt.out, ev, opt.figures);
}

JointSide run_joint_side(const std::string& name, const std::map<std::string, JointFitEntry>& fits,
                         std::map<std::string, FitSpec>& specs) {
  JointSide s;
  const auto it = fits.find(name);
  if (it == fits.end()) return s;
  s.fit = it->second;
  if (s.fit.status != "ok") {
    s.missing =
        "joint calibration " + s.fit.status + " (" + s.fit.fit_yaml.generic_string() + ": " + s.fit.failure + ")";
    return s;
  }
  const std::string key = s.fit.fit_file.generic_string();
  if (!specs.count(key)) {
    if (key.empty() || !fs::exists(s.fit.fit_file)) {
      s.missing = "fit file `" + key + "` (named by " + s.fit.fit_yaml.generic_string() + ") not found";
      return s;
    }
    specs.emplace(key, load_fit(s.fit.fit_file));
  }
  const FitSpec& spec = specs.at(key);
  const auto fe = std::find_if(spec.experiments.begin(), spec.experiments.end(),
                               [&](const FitExperiment& e) { return e.name == name; });
  if (fe == spec.experiments.end() || !fe->force || spec.objective != FitObjective::area_and_force) {
    s.missing = "`" + key + "` has no area_and_force experiment " + name;
    return s;
  }
  std::vector<SceneSetting> settings;
  for (const auto& [k, p] : s.fit.parameters) settings.push_back({k, p.value});
  const Scene scene = fe->scene.build(settings);
  const RunResult r = simulate(scene);
  s.ran = true;
  s.missing.clear();
  s.obs = r.obs;
  s.wall_s = r.obs.wall_s;
  s.objective = area_and_force_terms(scene, r.obs, r.recorder.loading_branch(), r.recorder.series(), *fe, spec.noise,
                                     spec.force_score)
                    .total();
  s.force = force_misfit(r.recorder.series(), *fe->force, spec.noise.force);
  if (scene.experiment.measured) {
    const auto& a0 = scene.experiment.junctions.area_m2;
    s.shape = compare_shapes(r.recorder.loading_branch(), *scene.experiment.measured,
                             std::accumulate(a0.begin(), a0.end(), 0.0));
  }
  return s;
}

std::vector<JointRow> run_joint_rows(const InteractionStudyOptions& opt, const std::vector<StudyRow>& rows) {
  const auto indep = read_joint_fits(opt.joint_independent);
  const auto inter = read_joint_fits(opt.joint_interacting);
  std::map<std::string, FitSpec> specs;
  std::vector<JointRow> out;
  for (const StudyRow& sr : rows) {
    JointRow r{sr.name, run_joint_side(sr.name, indep, specs), run_joint_side(sr.name, inter, specs)};
    if (opt.log)
      *opt.log << "  " << r.name << " joint: Q(t) rms independent " << io::format_cell("%.2f", r.indep.force.rms * 1e3)
               << " mN, interacting " << io::format_cell("%.2f", r.inter.force.rms * 1e3) << " mN (noise 95 % "
               << io::format_cell("%.2f", r.indep.ran ? r.indep.force.noise_p95 * 1e3 : r.inter.force.noise_p95 * 1e3)
               << " mN; " << io::format_cell("%.1f", r.inter.wall_s) << " s)" << std::endl;
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace

std::string run_interaction_study(const InteractionStudyOptions& opt) {
  const auto alpha_indep = calibrated_alpha_b(opt.fit_independent);
  const auto alpha_inter = calibrated_alpha_b(opt.fit_interacting);
  fs::path spread_scene;
  const std::vector<StudyRow> rows = run_rows(opt, alpha_indep, alpha_inter, spread_scene);
  Spread sp;
  if (!spread_scene.empty() && alpha_inter.count(opt.spread_experiment))
    sp = force_spread(spread_scene, alpha_inter.at(opt.spread_experiment), opt.spread_experiment);

  fs::create_directories(opt.out);
  write_table_csv(opt.out, rows);
  std::string fig_note;
  if (sp.ran) {
    write_forces_csv(opt.out, sp);
    fig_note = draw_force_spread(opt, sp);
  }
  const std::string pairs_md = sp.ran ? write_pairs(opt, sp) : std::string();
  // A(Q) of the spread experiment: measured, independent, interacting (calibrated).
  // (Kept to the table: the loading branches are in the runs' observables only.)
  const Tally t = tally_rows(rows);
  const std::string verdict = verdict_of(t);
  const std::vector<JointRow> joint = run_joint_rows(opt, rows);
  write_joint_csv(opt.out, joint);
  write_report_md(opt, rows, t, verdict, joint, joint_verdict(tally_joint(joint), rows.size()), sp, fig_note, pairs_md);
  return verdict;
}

}  // namespace asperity
