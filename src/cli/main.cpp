// asperity: onset of sliding of rough elastomer contacts (independent-asperity model).
// Parses the command line and dispatches to one subcommand (see cli/commands.hpp).
#include <exception>
#include <iostream>
#include <vector>

#include "cli/commands.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"

int main(int argc, char** argv) {
  namespace cli = asperity::cli;
  CLI::App app{"asperity: onset of sliding of elastomer multicontacts "
               "(independent-asperity model, Scheibert, Sahli & Peyrard 2020)"};
  app.set_version_flag("--version", std::string("asperity ") + ASPERITY_VERSION + " (" +
                                        ASPERITY_BUILD_TYPE + ")");
  app.require_subcommand(1);

  // Registration: one line per subcommand.
  std::vector<cli::Command> commands;
  commands.push_back(cli::add_run_command(app));
  commands.push_back(cli::add_sweep_command(app));
  commands.push_back(cli::add_merge_command(app));
  commands.push_back(cli::add_plot_command(app));
  commands.push_back(cli::add_fit_command(app));
  commands.push_back(cli::add_generate_command(app));
  commands.push_back(cli::add_reproduce_command(app));
  commands.push_back(cli::add_bench_command(app));
  commands.push_back(cli::add_regress_command(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  // Dispatch.
  try {
    for (const auto& c : commands)
      if (c.sub->parsed()) return c.run();
  } catch (const asperity::InputError& e) {
    std::cerr << e.what() << '\n';
    return cli::exit_input;
  } catch (const asperity::SolverError& e) {
    std::cerr << "solver error: " << e.what() << '\n';
    return cli::exit_solver;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return cli::exit_failure;
  }
  std::cerr << app.help();
  return cli::exit_input;
}
