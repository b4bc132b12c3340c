// asperity generate [--recipe data/standin/recipe.yaml] [--out data/standin] [--scenes DIR] [--quiet]
// Rebuilds the stand-in experiments (docs/model.md §7) from their recipe; same recipe, same bytes.
// A recipe with a `topography:` section (generate/topography.hpp, docs/topography.md) instead
// writes one experiment whose junctions are the contact clusters of a surface under a sphere; one
// with a `synthetic:` section (generate/synthetic.hpp) one experiment whose measured A(Q) and Q(t)
// come from one run of a scene at known model settings, plus noise.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "cli/options.hpp"
#include "generate/recipe.hpp"
#include "generate/standin.hpp"
#include "generate/synthetic.hpp"
#include "generate/topography.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "report/output_dir.hpp"

namespace asperity::cli {
namespace {

struct GenerateCliOptions {
  std::string recipe = "data/standin/recipe.yaml";
  std::string out = "data/standin";
  std::string scenes;
  bool quiet = false;
  int threads = 0;  // -j: the topography contact solve's threads (0: every hardware thread)
};

// Its own marker: a stand-in folder is never taken for a topography output, nor the reverse.
constexpr const char* kTopographyMarker = "generate topography";

int generate_topography(const GenerateCliOptions& o) {
  const TopographyRecipe recipe = load_topography_recipe(o.recipe);
  if (!o.scenes.empty())
    throw io::InputError("--scenes", 0, "",
                         "a topography recipe writes one experiment and no scenes; leave out --scenes");
  check_publishable(o.out, kTopographyMarker, "--out");  // before the solve: a refused folder costs nothing
  const TopographyJunctions t = build_topography_junctions(recipe, threads_or_all(o.threads));
  publish_dir(o.out, kTopographyMarker, "--out",
              [&](const std::filesystem::path& tmp) { write_topography_experiment(recipe, t, tmp); });
  if (!o.quiet) {
    double total = 0;
    for (const double A : t.experiment.junctions.area_m2) total += A;
    std::cout << "wrote " << t.experiment.junctions.size() << " junctions (" << t.clusters << " contact clusters, "
              << t.merges << " merges of overlapping discs, total area " << io::format_short(total)
              << " m^2; contact solve " << t.iterations << " iterations) to " << o.out
              << "/junctions.csv and experiment.yaml\n";
  }
  return exit_ok;
}

// Its own marker too: a synthetic experiment is never taken for a stand-in or topography output.
constexpr const char* kSyntheticMarker = "generate synthetic";

int generate_synthetic(const GenerateCliOptions& o) {
  const SyntheticRecipe recipe = load_synthetic_recipe(o.recipe);
  if (!o.scenes.empty())
    throw io::InputError("--scenes", 0, "",
                         "a synthetic recipe writes one experiment folder (with its scene.yaml); leave out --scenes");
  check_publishable(o.out, kSyntheticMarker, "--out");  // before the run: a refused folder costs no simulation
  const SyntheticExperiment x = build_synthetic(recipe);
  publish_dir(o.out, kSyntheticMarker, "--out",
              [&](const std::filesystem::path& tmp) { write_synthetic_experiment(recipe, x, tmp); });
  if (!o.quiet)
    std::cout << "wrote the SYNTHETIC experiment " << x.experiment.name << " (" << x.experiment.junctions.size()
              << " junctions, Q_s = " << io::format_short(x.model.Q_s)
              << " N at t = " << io::format_short(x.model.t_peak) << " s; " << x.experiment.measured->Q_N.size()
              << " A(Q) and " << x.force.t_s.size() << " Q(t) samples) to " << o.out << "\n";
  return exit_ok;
}

int generate(const GenerateCliOptions& o) {
  if (is_topography_recipe(o.recipe)) return generate_topography(o);
  if (is_synthetic_recipe(o.recipe)) return generate_synthetic(o);
  const StandinRecipe recipe = load_recipe(o.recipe);
  // Like run and fit: each file replaced only when this command wrote it there, unchanged since.
  check_publishable(o.out, "generate", "--out");
  if (!o.scenes.empty()) check_publishable(o.scenes, "generate", "--scenes");
  const auto xs = build_standins(recipe, o.quiet ? nullptr : &std::cout);
  const std::filesystem::path out = normal_dir(o.out), scenes = o.scenes.empty() ? out : normal_dir(o.scenes);
  // One folder for both: one publish, else each would take the other's files for stale ones.
  publish_dir(o.out, "generate", "--out", [&](const std::filesystem::path& tmp) {
    write_standin_experiments(recipe, xs, tmp);
    if (!o.scenes.empty() && scenes == out) write_standin_scenes(recipe, xs, tmp, out, out);
  });
  if (!o.scenes.empty() && scenes != out)
    publish_dir(o.scenes, "generate", "--scenes",
                [&](const std::filesystem::path& tmp) { write_standin_scenes(recipe, xs, tmp, scenes, out); });
  if (!o.quiet) {
    std::cout << "wrote " << xs.size() << " stand-in experiments and README.md to " << o.out;
    if (!o.scenes.empty()) std::cout << ", scenes to " << o.scenes;
    std::cout << '\n';
  }
  return exit_ok;
}

}  // namespace

Command add_generate_command(CLI::App& app) {
  auto opt = std::make_shared<GenerateCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "generate",
      "Generate the stand-in experiments (junctions, stand-in measured A(Q), README) from a recipe, with a "
      "topography recipe one experiment whose junctions are the contact clusters of a surface under a sphere, or with "
      "a "
      "synthetic recipe one experiment whose A(Q) and Q(t) come from one run of a scene at known model settings");
  sub->add_option("--recipe,-r", opt->recipe, "Recipe YAML")->capture_default_str();
  sub->add_option("--out,-o", opt->out, "Output folder (one P<load>N/ subfolder per experiment)")
      ->capture_default_str();
  sub->add_option("--scenes", opt->scenes,
                  "Also write one paper scene per experiment into this folder (e.g. scenes/paper)");
  add_threads_option(sub, opt->threads, "the topography contact solve's FFTs and sums (same bytes with any count)");
  add_quiet_flag(sub, opt->quiet);
  return Command{sub, [opt](const Invocation&) { return generate(*opt); }};
}

}  // namespace asperity::cli
