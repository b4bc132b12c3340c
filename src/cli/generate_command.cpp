// asperity generate [--recipe data/standin/recipe.yaml] [--out data/standin] [--scenes DIR] [--quiet]
// Rebuilds the stand-in experiments (MODEL.md §7) from their recipe; same recipe, same bytes.
// A recipe with a `topography:` section (generate/topography.hpp, docs/topography.md) instead
// writes one experiment whose junctions are the contact clusters of a surface under a sphere; one
// with a `synthetic:` section (generate/synthetic.hpp) one experiment whose measured A(Q) and Q(t)
// come from one run of a scene at known model settings, plus noise.
#include <filesystem>
#include <fstream>
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

// Folders written before markers existed: the stand-in README's first line, or scenes that all
// say they were written by `asperity generate --scenes`.
bool standin_folder(const std::filesystem::path& d) {
  return first_line_is(d / "README.md", "# Stand-in experiments — NOT measurements");
}
bool scenes_folder(const std::filesystem::path& d) {
  bool any = false;
  for (const auto& e : std::filesystem::directory_iterator(d)) {
    if (e.path().filename() == kMarkerFile) continue;
    std::ifstream in(e.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (e.path().extension() != ".yaml" || text.find("Written by `asperity generate --scenes`") == std::string::npos)
      return false;
    any = true;
  }
  return any;
}

// Its own marker: a stand-in folder is never taken for a topography output, nor the reverse.
constexpr const char* kTopographyMarker = "generate topography";

int generate_topography(const GenerateCliOptions& o) {
  const TopographyRecipe recipe = load_topography_recipe(o.recipe);
  if (!o.scenes.empty())
    throw InputError("--scenes", 0, "", "a topography recipe writes one experiment and no scenes; leave out --scenes");
  check_ours(o.out, kTopographyMarker, "--out");
  const TopographyJunctions t = build_topography_junctions(recipe, threads_or_all(o.threads));
  write_topography_experiment(recipe, t, o.out);
  write_marker(o.out, kTopographyMarker);
  if (!o.quiet) {
    double total = 0;
    for (const double A : t.experiment.junctions.area_m2) total += A;
    std::cout << "wrote " << t.experiment.junctions.size() << " junctions (" << t.clusters << " contact clusters, "
              << t.merges << " merges of overlapping discs, total area " << scene_io::format_short(total)
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
    throw InputError("--scenes", 0, "", "a synthetic recipe writes one experiment folder (with its scene.yaml); leave out --scenes");
  check_ours(o.out, kSyntheticMarker, "--out");  // before the run: a refused folder costs no simulation
  const SyntheticExperiment x = build_synthetic(recipe);
  claim_dir(o.out, kSyntheticMarker, "--out");   // marked before any file: a rerun may replace a partial folder
  write_synthetic_experiment(recipe, x, o.out);
  if (!o.quiet)
    std::cout << "wrote the SYNTHETIC experiment " << x.experiment.name << " (" << x.experiment.junctions.size()
              << " junctions, Q_s = " << scene_io::format_short(x.model.Q_s) << " N at t = "
              << scene_io::format_short(x.model.t_peak) << " s; " << x.experiment.measured->Q_N.size()
              << " A(Q) and " << x.force.t_s.size() << " Q(t) samples) to " << o.out << "\n";
  return exit_ok;
}

int generate(const GenerateCliOptions& o) {
  if (is_topography_recipe(o.recipe)) return generate_topography(o);
  if (is_synthetic_recipe(o.recipe)) return generate_synthetic(o);
  const StandinRecipe recipe = load_recipe(o.recipe);
  check_ours(o.out, "generate", "--out", standin_folder);
  if (!o.scenes.empty()) check_ours(o.scenes, "generate", "--scenes", scenes_folder);
  GenerateOptions g;
  g.out_dir = o.out;
  g.scenes_dir = o.scenes;
  g.log = o.quiet ? nullptr : &std::cout;
  const auto xs = generate_standins(recipe, g);
  write_marker(o.out, "generate");
  if (!o.scenes.empty()) write_marker(o.scenes, "generate");
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
      "generate", "Generate the stand-in experiments (junctions, stand-in measured A(Q), README) from a recipe, with a "
      "topography recipe one experiment whose junctions are the contact clusters of a surface under a sphere, or with a "
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
