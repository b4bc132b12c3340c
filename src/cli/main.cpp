// asperity: onset of sliding of rough elastomer contacts (independent-asperity model).
// Parses the command line and dispatches to one subcommand (see cli/commands.hpp).
#include <cctype>
#include <cstring>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "io/provenance.hpp"
#include "io/temp_files.hpp"
#include "scene/load.hpp"
#include "solve/integrate.hpp"

namespace {

// One line on stderr, whatever the text holds.
void print_line(const std::string& prefix, const std::string& text) {
  std::string s = prefix + text;
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  std::cerr << s << '\n';
}

// The command line as a user would type it again: "asperity" and the arguments, each quoted
// for a POSIX shell when it holds anything but [A-Za-z0-9_./=:,+-].
std::string command_line_text(int argc, char** argv) {
  std::string line = "asperity";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    bool plain = !a.empty();
    for (const char c : a)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || std::strchr("_./=:,+-@%", c))) plain = false;
    line += ' ';
    if (plain) {
      line += a;
      continue;
    }
    line += '\'';
    for (const char c : a) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
    line += '\'';
  }
  return line;
}

int run_cli(int argc, char** argv) {
  namespace cli = asperity::cli;
  CLI::App app{
      "asperity: onset of sliding of elastomer multicontacts "
      "(independent-asperity model, Scheibert, Sahli & Peyrard 2020)"};
  app.set_version_flag("--version", asperity::io::version_line());
  app.require_subcommand(1);

  // Registration: one line per subcommand.
  std::vector<cli::Command> commands;
  commands.push_back(cli::add_run_command(app));
  commands.push_back(cli::add_sweep_command(app));
  commands.push_back(cli::add_merge_command(app));
  commands.push_back(cli::add_export_command(app));
  commands.push_back(cli::add_plot_command(app));
  commands.push_back(cli::add_fit_command(app));
  commands.push_back(cli::add_generate_command(app));
  commands.push_back(cli::add_reproduce_command(app));
  commands.push_back(cli::add_bench_command(app));
  commands.push_back(cli::add_regress_command(app));
  commands.push_back(cli::add_study_command(app));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print as CLI11 does; a command-line error is a user error like any
    // other bad input: one line, exit 2 (CLI11's own codes, 105, 106, ..., are undocumented).
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    std::string what = e.what();
    if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {  // CLI11 only says one is required
      what = "unknown command '" + std::string(argv[1]) + "'; commands:";
      for (const auto& c : commands) what += " " + c.sub->get_name();
    }
    print_line("asperity: ", what + " (asperity --help)");
    return cli::exit_input;
  }

  // Dispatch.
  const cli::Invocation invocation{command_line_text(argc, argv)};
  try {
    for (const auto& c : commands)
      if (c.sub->parsed()) return c.run(invocation);
  } catch (const asperity::io::InputError& e) {
    print_line("", e.what());
    return cli::exit_input;
  } catch (const asperity::SolverError& e) {
    print_line("solver error: ", e.what());
    return cli::exit_solver;
  }
  std::cerr << app.help();
  return cli::exit_input;
}

}  // namespace

// Everything that escapes a command (a library's exception, memory exhausted) becomes one line
// and a non-zero exit, never std::terminate's "terminate called after...".
int main(int argc, char** argv) {
  asperity::io::install_signal_cleanup();  // SIGINT/SIGTERM/SIGHUP remove our temporaries; SIGXFSZ -> EFBIG
  try {
    return run_cli(argc, argv);
  } catch (const std::bad_alloc&) {
    print_line("error: ", "out of memory");
  } catch (const std::exception& e) {
    print_line("error: ", e.what());
  } catch (...) {
    print_line("error: ", "unknown exception");
  }
  return asperity::cli::exit_failure;
}
