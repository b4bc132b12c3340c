#include "fit/fit_problem.hpp"

#include <omp.h>

#include <cmath>
#include <exception>
#include <stdexcept>

#include "batch/parallel_runner.hpp"
#include "batch/stop_flag.hpp"
#include "fit/fit_journal.hpp"
#include "fit/objective.hpp"
#include "io/numbers.hpp"
#include "io/provenance.hpp"
#include "observe/simulate.hpp"

namespace asperity::fit_detail {

namespace {

// One experiment at the settings. RunInterrupted (the stop's) passes through: the evaluation is
// abandoned, not failed.
ExperimentEval run_experiment(const FitSpec& spec, std::size_t e, const std::vector<SceneSetting>& settings, bool keep,
                              const RunMonitor* monitor, const UserTerm* user_term) {
  omp_set_num_threads(1);  // this task is one of `threads` workers: no nested OpenMP team
  ExperimentEval out;
  try {
    const FitExperiment& fe = spec.experiments[e];
    Scene scene = fe.scene.build(settings);
    if (fe.measured_override) scene.experiment.measured = *fe.measured_override;
    RunResult r = simulate(scene, 0, monitor);
    if (spec.objective == FitObjective::user) {
      if (!user_term || !*user_term)
        throw std::invalid_argument("run_fit: the user objective needs FitOptions::user_term");
      out.residual = (*user_term)(fe, scene, r);
    } else if (spec.objective == FitObjective::area_and_force) {
      out.terms = area_and_force_terms(scene, r.obs, r.recorder.loading_branch(), r.recorder.series(), fe, spec.noise,
                                       spec.force_score);
      out.residual = out.terms.total();
    } else {
      out.residual = experiment_residual(spec.objective, scene, r.obs, r.recorder.loading_branch(), fe.target);
    }
    if (std::isnan(out.residual) && spec.objective == FitObjective::user) {
      out.error = "objective term of " + fe.name + " is NaN (the user objective returned nan)";
    } else if (std::isnan(out.residual)) {
      out.error = "objective term of " + fe.name + " is NaN (model alpha = " + io::format_significant(r.obs.alpha) +
                  ", measured alpha = " + io::format_significant(r.obs.alpha_measured) +
                  ", Q_s = " + io::format_significant(r.obs.Q_s) +
                  ", loading-branch points = " + std::to_string(r.recorder.loading_branch().size()) + ")";
    } else if (!r.obs.peak_found && spec.objective != FitObjective::area_and_force) {
      // (area_and_force compares the whole measured Q(t) window, peak or not: a model without a
      // peak there is a poor fit, scored as such, not a broken run.)
      // Without a confirmed peak, Q_s, the loading branch and every objective built on them
      // come from wherever the run stopped: a number, but not the one the fit is about.
      out.error = fe.name + " (" + io::result_path(scene.experiment.file) +
                  "): no confirmed static friction peak before stop.time = " + io::format_significant(scene.stop.time) +
                  " s (highest Q " + io::format_significant(r.obs.Q_s) +
                  " N at t = " + io::format_significant(r.obs.t_peak) +
                  " s); the objective would use an unfinished loading branch: raise stop.time";
    }
    if (keep) {
      out.obs = r.obs;
      out.loading = r.recorder.loading_branch();
      out.mass_kg = scene.experiment.mass_kg;
      out.stand_in = is_stand_in(scene.experiment);
      out.measured = scene.experiment.measured;
      if (spec.objective == FitObjective::area_and_force) out.series = r.recorder.series();
    }
  } catch (const RunInterrupted&) {
    throw;
  } catch (const std::exception& ex) {
    out.error = spec.experiments[e].name + ": " + ex.what();
  }
  return out;
}

std::vector<SceneSetting> settings_for(const Problem& pb, std::size_t k, const std::vector<double>& x) {
  std::vector<SceneSetting> s = pb.extra[k];
  for (std::size_t i = 0; i < pb.vars.size(); ++i) {
    const FreeVariable& v = pb.vars[i];
    if (v.experiment < 0 || static_cast<std::size_t>(v.experiment) == pb.exps[k])
      s.push_back({pb.spec->parameters[v.parameter].key, x[i]});
  }
  return s;
}

}  // namespace

void tick(const Problem& pb, const char* part, double objective) {
  if (pb.ticked) ++*pb.ticked;
  if (pb.on_evaluation && *pb.on_evaluation) (*pb.on_evaluation)(FitTick{&pb.label, part, objective, 0});
}

Evaluation evaluate(const Problem& pb, const std::vector<double>& x, std::vector<ExperimentEval>* runs) {
  const auto t0 = Clock::now();
  std::vector<ExperimentEval> r(pb.exps.size());
  // Isolated: a thread waiting here runs only these runs, never another task's optimizer (so
  // each nlopt::opt stays on its own thread, with no nested optimize on one stack).
  for_each_nested(
      pb.exps.size(),
      [&](std::size_t k) {
        r[k] = run_experiment(*pb.spec, pb.exps[k], settings_for(pb, k, x), runs != nullptr,
                              pb.stop ? pb.stop->monitor() : nullptr, pb.user_term);
      },
      Nesting::isolated);
  Evaluation ev;
  ev.values = x;
  ev.objective = 0;
  for (const auto& e : r) {
    ev.residuals.push_back(e.residual);
    ev.objective += e.residual;
    if (!e.error.empty() && ev.status == "ok") ev.status = e.error;
  }
  if (ev.status == "ok" && !std::isfinite(ev.objective))
    ev.status = "objective is not finite: " + io::format_significant(ev.objective);
  if (ev.status != "ok") ev.objective = Observables::nan;
  ev.wall_s = seconds_since(t0);
  if (runs) *runs = std::move(r);
  return ev;
}

std::string values_text(const Problem& pb, const std::vector<double>& x, bool every_digit) {
  std::string s;
  for (std::size_t i = 0; i < x.size(); ++i)
    s += (i ? ", " : "") + pb.vars[i].label + " = " +
         (every_digit ? io::format_double(x[i]) : io::format_significant(x[i]));
  return s;
}

std::optional<Evaluation> evaluate_journaled(const Problem& pb, int index, const std::vector<double>& x) {
  if (pb.journal) {
    if (std::optional<Evaluation> ev = pb.journal->find(pb.part, pb.label, x)) {
      ev->index = index;
      if (pb.counts) ++pb.counts->replayed;
      return ev;
    }
    if (pb.replay_only) return std::nullopt;
  }
  Evaluation ev = evaluate(pb, x);
  ev.index = index;
  if (pb.journal) pb.journal->append(pb.part, pb.label, ev);
  if (pb.counts) ++pb.counts->computed;
  return ev;
}

std::string not_journaled_text(const Problem& pb, int index, const std::vector<double>& x) {
  return "evaluation " + std::to_string(index) + " of " + pb.part + " " + pb.label + " (" + values_text(pb, x) +
         ") is in no journal";
}

}  // namespace asperity::fit_detail
