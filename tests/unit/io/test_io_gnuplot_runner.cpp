// io/gnuplot_runner.hpp: gnuplot started without a shell, script on its standard input.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "io/gnuplot_runner.hpp"
#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;
using asperity::testing::slurp;

TEST_CASE("run_gnuplot runs the script in the given folder, never through a shell", "[io][gnuplot]") {
  if (!io::gnuplot_available()) return;  // nothing to check without gnuplot (CI installs it)
  const fs::path root = asperity::testing::temp_path("asperity-io-gnuplot");
  fs::remove_all(root);
  // A folder name a shell would expand and run: posix_spawn + chdir take it as bytes.
  const fs::path dir = root / "a b $(touch pwned) `touch pwned2`; touch pwned3";
  fs::create_directories(dir);
  io::run_gnuplot(dir, "set print 'out.txt'\nprint 6*7\nprint sqrt(2.25)\n");
  CHECK(slurp(dir / "out.txt") == "42\n1.5\n");
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) files += e.is_regular_file();
  CHECK(files == 1);  // out.txt only: nothing was run by a shell
  fs::remove_all(root);
}

TEST_CASE("run_gnuplot reports gnuplot's error line and status", "[io][gnuplot]") {
  if (!io::gnuplot_available()) return;  // nothing to check without gnuplot (CI installs it)
  try {
    io::run_gnuplot(fs::temp_directory_path(), "print 1\nnot_a_command 3\n");
    FAIL("no exception");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.rfind("gnuplot failed (status ", 0) == 0);
    CHECK(what.find("): ") != std::string::npos);
    CHECK(what.find("invalid command") != std::string::npos);  // gnuplot's own line, not "print 1"'s output
  }
}
