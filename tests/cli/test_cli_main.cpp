// The command line's own errors (cli/main.cpp): like every bad input, one line on stderr and
// exit 2, naming what was wrong; --help and --version still exit 0.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_spawn.hpp"

using namespace asperity::testing;
using Catch::Contains;

namespace {

std::size_t lines(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("command-line errors exit 2 with one line naming the problem", "[cli_main]") {
  const std::filesystem::path work = std::filesystem::temp_directory_path();
  struct Case {
    std::vector<std::string> args;
    const char* names;  // what the line must mention
  };
  const std::vector<Case> cases{
      {{"run", "--no-such-flag", "x.yaml"}, "--no-such-flag"},  // CLI11: 109 (extras)
      {{"run"}, "scene"},                                       // 106 (required positional)
      {{"no-such-command"}, "no-such-command"},                 // 109
      {{"bench", "--repeats", "0", "speed"}, "--repeats"},      // 105 (validation)
      {{"run", "x.yaml", "--set"}, "--set"},                    // 107 (argument missing)
  };
  for (const auto& c : cases) {
    const CliResult r = run_argv(work, c.args);
    INFO(c.args[0] << " ... -> exit " << r.status << ", stderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(lines(r.err) == 1);
    CHECK_THAT(r.err, Contains(c.names));
    CHECK(r.out.empty());
  }
}

TEST_CASE("help and version (--help, --version) exit 0 and print on stdout", "[cli_main]") {
  const std::filesystem::path work = std::filesystem::temp_directory_path();
  const CliResult v = run_argv(work, {"--version"});
  CHECK(v.status == 0);
  CHECK_THAT(v.out, Contains("asperity "));
  const CliResult h = run_argv(work, {"run", "--help"});
  CHECK(h.status == 0);
  CHECK_THAT(h.out, Contains("--set"));
}
