// asperity study interactions [SCENE.yaml...] [--out results/interactions] [--fit-independent F]
//                             [--fit-interacting F] [--joint-independent F...] [--joint-interacting F...]
//                             [--sweep STORE] [--topography TABLE] [--recovery MATRIX] [--spread EXPERIMENT]
//                             [--quiet]
// asperity study recovery [--recipes R.yaml...] [--out results/recovery] [-j N] [--quiet]
// asperity study continuum [--recipe R.yaml] [--loads P...] [--out results/continuum] [--points N] [-j N]
//                          [--figures F] [--quiet]
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "bench/bench_scene.hpp"
#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "report/output_dir.hpp"
#include "studies/continuum_comparison.hpp"
#include "studies/interaction_study.hpp"
#include "studies/recovery_matrix.hpp"

namespace asperity::cli {

Command add_study_command(CLI::App& app) {
  CLI::App* sub = app.add_subcommand("study", "Studies that compare model variants on the stand-ins");
  sub->require_subcommand(1);
  auto opt = std::make_shared<InteractionStudyOptions>();
  auto scenes = std::make_shared<std::vector<std::string>>();
  auto out = std::make_shared<std::string>("results/interactions");
  auto quiet = std::make_shared<bool>(false);
  CLI::App* in = sub->add_subcommand(
      "interactions",
      "Elastic interactions vs independent junctions, each at its calibrated alpha_b: shape exponent, "
      "area decay, incipient slope, stick-slip, force spread at the peak, the crowding/cut-off sweep");
  in->add_option("scenes", *scenes, "Scenes (default scenes/paper/P*.yaml)")->check(CLI::ExistingFile);
  in->add_option("-o,--out", *out, "Output folder (default results/interactions)");
  in->add_option("--fit-independent", opt->fit_independent, "fit.yaml of the independent calibration");
  in->add_option("--fit-interacting", opt->fit_interacting, "fit.yaml of the interacting calibration");
  in->add_option("--joint-independent", opt->joint_independent,
                 "fit.yaml file(s) of the joint (alpha_b, epsilon, eta) calibration, independent junctions");
  in->add_option("--joint-interacting", opt->joint_interacting,
                 "fit.yaml file(s) of the joint (alpha_b, epsilon, eta) calibration, interacting junctions");
  in->add_option("--sweep", opt->sweep_store, "Store of sweeps/interactions.yaml");
  in->add_option("--topography", opt->topography_table,
                 "table.csv of the topography study (default results/topography/table.csv)");
  in->add_option("--recovery", opt->recovery_matrix,
                 "matrix.csv of `asperity study recovery` (default results/recovery/matrix.csv)");
  in->add_option("--spread", opt->spread_experiment, "Experiment of the force-spread histogram (default P4.00N)");
  add_figures_option(in, opt->figures);
  in->add_flag("-q,--quiet", *quiet, "Print nothing on success");
  auto rec = std::make_shared<RecoveryMatrixOptions>();
  auto rec_out = std::make_shared<std::string>("results/recovery");
  auto rec_recipes = std::make_shared<std::vector<std::string>>();
  CLI::App* rc = sub->add_subcommand(
      "recovery",
      "The recovery matrix: SYNTHETIC experiments made by each model at a known truth, each fitted by "
      "each model at equal budgets; whether the joint calibration tells the models apart, per load");
  rc->add_option("--recipes", *rec_recipes,
                 "Synthetic recipes, one per load and model (default examples/recovery/recipe_*.yaml)")
      ->check(CLI::ExistingFile);
  rc->add_option("-o,--out", *rec_out, "Output folder (default results/recovery)");
  rc->add_option("-j,--threads", rec->threads, "Threads of each fit (default 2)")->check(CLI::Range(1, 1024));
  rc->add_flag("-q,--quiet", *quiet, "Print nothing on success");
  Command recovery{rc, [rec, rec_out, rec_recipes, quiet](const Invocation&) {
                     RecoveryMatrixOptions o = *rec;
                     o.out = *rec_out;
                     check_ours(o.out, "study recovery", "--out");
                     if (!rec_recipes->empty()) o.recipes.assign(rec_recipes->begin(), rec_recipes->end());
                     o.log = *quiet ? nullptr : &std::cout;
                     const std::vector<RecoveryCell> cells = run_recovery_matrix(o);
                     write_marker(o.out, "study recovery");
                     if (!*quiet) {
                       for (const LoadVerdict& v : judge_loads(cells))
                         std::printf("%s: %s\n", v.load.c_str(), v.verdict.c_str());
                       std::printf("-> %s/REPORT.md\n", o.out.string().c_str());
                     }
                     return exit_ok;
                   }};
  auto con = std::make_shared<ContinuumStudyOptions>();
  con->recipe = "results/topography/recipe.yaml";
  // The paper's six loads (docs/model.md §2) and three lighter ones, where the junctions are fewer,
  // sparser and smaller (3 to 7 pixels each on the default recipe's map).
  con->loads_N = {0.02, 0.1, 0.3, 0.98, 1.52, 2.07, 3.09, 4.00, 6.40};
  con->out = "results/continuum";
  CLI::App* cn = sub->add_subcommand(
      "continuum",
      "Junction models (independent, interacting) against the continuum tangential contact on the same "
      "contact map, per load (SYNTHETIC surfaces): stiffness and Q(delta) errors against coverage, the rule");
  cn->add_option("--recipe", con->recipe, "Topography recipe (default results/topography/recipe.yaml)")
      ->check(CLI::ExistingFile);
  cn->add_option("--loads", con->loads_N, "Normal loads [N] (default 0.02, 0.1, 0.3 and the paper's six)")
      ->check(CLI::Range(1e-6, 1e6));
  cn->add_option("-o,--out", con->out, "Output folder (default results/continuum)");
  cn->add_option("--points", con->points, "Displacements of each Q(delta) (default 32)")->check(CLI::Range(2, 10000));
  cn->add_option("-j,--threads", con->threads, "Threads of the contact solves (default 1)")->check(CLI::Range(1, 1024));
  add_figures_option(cn, con->figures);
  cn->add_flag("-q,--quiet", *quiet, "Print nothing on success");
  Command continuum{cn, [con, quiet](const Invocation&) {
                      ContinuumStudyOptions o = *con;
                      check_ours(o.out, "study continuum", "--out");
                      o.log = *quiet ? nullptr : &std::cout;
                      run_continuum_study(o);
                      write_marker(o.out, "study continuum");
                      if (!*quiet) std::printf("-> %s/REPORT.md\n", o.out.string().c_str());
                      return exit_ok;
                    }};
  return Command{sub, [opt, scenes, out, quiet, recovery, continuum](const Invocation& inv) {
                   if (recovery.sub->parsed()) return recovery.run(inv);
                   if (continuum.sub->parsed()) return continuum.run(inv);
                   InteractionStudyOptions o = *opt;
                   o.out = *out;
                   check_ours(o.out, "study interactions", "--out");
                   if (scenes->empty())
                     o.scenes = paper_scenes("scenes/paper");
                   else
                     o.scenes.assign(scenes->begin(), scenes->end());
                   o.log = *quiet ? nullptr : &std::cout;
                   const std::string verdict = run_interaction_study(o);
                   write_marker(o.out, "study interactions");
                   if (!*quiet) std::printf("%s\n-> %s/REPORT.md\n", verdict.c_str(), o.out.string().c_str());
                   return exit_ok;
                 }};
}

}  // namespace asperity::cli
