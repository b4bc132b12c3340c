#pragma once
// Subcommands of the `asperity` executable. Each lives in its own src/cli/<name>_command.cpp,
// declares its add_* function here and is registered by one line in main.cpp (the library is
// static, so self-registration would be dropped by the linker).
//
// add_* adds the subcommand and its options to `app` and returns the function main calls when
// that subcommand was given. The function returns the exit code; it may instead throw
// InputError (→ exit 2, what() printed as is) or SolverError (→ exit 3), which main maps.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace asperity::cli {

inline constexpr int exit_ok = 0;
inline constexpr int exit_failure = 1;        // command ran but its check failed (e.g. regress)
inline constexpr int exit_input = 2;          // bad scene / arguments (InputError)
inline constexpr int exit_solver = 3;         // solver could not go on (SolverError)
inline constexpr int exit_interrupted = 130;  // Ctrl-C (128 + SIGINT, as shells report it)

// What every command may record of how it was called (provenance of its results).
struct Invocation {
  std::string command_line;  // "asperity sweep c.yaml -j 2", arguments shell-quoted where needed
};

struct Command {
  CLI::App* sub = nullptr;  // the subcommand; main runs `run` when it was parsed
  std::function<int(const Invocation&)> run;
};

// asperity run SCENE.yaml [--out DIR] [--set key=value]... [--quiet] [--plot]
Command add_run_command(CLI::App& app);  // run_command.cpp

// asperity generate [--recipe data/standin/recipe.yaml] [--out data/standin] [--scenes DIR] [--quiet]
Command add_generate_command(CLI::App& app);  // generate_command.cpp

// asperity reproduce SCENE.yaml... [--out results/paper] [--set k=v]... [--threads N] [--quiet]
Command add_reproduce_command(CLI::App& app);  // reproduce_command.cpp

// asperity regress [--suite F] [--golden F] [--update --reason TEXT] [--threads N] [--all]
Command add_regress_command(CLI::App& app);  // regress_command.cpp

// asperity fit FIT.yaml [--out DIR] [--threads N] [--no-profile] [--no-error-bars] [--quiet]
Command add_fit_command(CLI::App& app);  // fit_command.cpp

// asperity bench tradeoff|accuracy|savings [--out results/bench] [--quick] [--repeats N] ...
Command add_bench_command(CLI::App& app);  // bench_command.cpp

// asperity sweep CAMPAIGN.yaml [--threads N] [--shard I/N] [--out DIR] [--quiet] [--retry-failed]
// (exit 1 when any point of the shard failed)
Command add_sweep_command(CLI::App& app);  // sweep_command.cpp

// asperity merge DIR1 DIR2 ... --out DIR
Command add_merge_command(CLI::App& app);  // merge_command.cpp

// asperity export STORE --sqlite FILE
Command add_export_command(CLI::App& app);  // export_command.cpp

// asperity plot STORE --x KEY --y KEY --z COLUMN [--where COL=VALUE]... [--out FILE.png]
Command add_plot_command(CLI::App& app);  // plot_command.cpp

// asperity study STUDY.yaml [--out DIR] [-j N] [--figures F] [--quiet]
Command add_study_command(CLI::App& app);  // study_command.cpp

}  // namespace asperity::cli
