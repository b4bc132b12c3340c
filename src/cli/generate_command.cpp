// asperity generate [--recipe data/standin/recipe.yaml] [--out data/standin] [--scenes DIR] [--quiet]
// Rebuilds the stand-in experiments (MODEL.md §7) from their recipe; same recipe, same bytes.
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "generate/recipe.hpp"
#include "generate/standin.hpp"

namespace asperity::cli {
namespace {

struct GenerateCliOptions {
  std::string recipe = "data/standin/recipe.yaml";
  std::string out = "data/standin";
  std::string scenes;
  bool quiet = false;
};

int generate(const GenerateCliOptions& o) {
  const StandinRecipe recipe = load_recipe(o.recipe);
  GenerateOptions g;
  g.out_dir = o.out;
  g.scenes_dir = o.scenes;
  g.log = o.quiet ? nullptr : &std::cout;
  const auto xs = generate_standins(recipe, g);
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
      "generate", "Generate the stand-in experiments (junctions, stand-in measured A(Q), README) from a recipe");
  sub->add_option("--recipe,-r", opt->recipe, "Recipe YAML")->capture_default_str();
  sub->add_option("--out,-o", opt->out, "Output folder (one P<load>N/ subfolder per experiment)")
      ->capture_default_str();
  sub->add_option("--scenes", opt->scenes,
                  "Also write one paper scene per experiment into this folder (e.g. scenes/paper)");
  sub->add_flag("--quiet,-q", opt->quiet, "Print nothing on success");
  return Command{sub, [opt] { return generate(*opt); }};
}

}  // namespace asperity::cli
