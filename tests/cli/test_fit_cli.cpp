// End to end: `asperity fit` writes results/fits/<name>/ and maps bad fit files to exit 2.
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "fit_support.hpp"
#include "io/hash.hpp"

#include "support_files.hpp"

using namespace asperity::testing;
namespace fs = std::filesystem;

namespace {

using asperity::testing::slurp;

int asperity_in(const fs::path& work, const std::string& args, std::string* err = nullptr) {
  const std::string cmd =
      "cd '" + work.string() + "' && '" + ASPERITY_BINARY + "' " + args + " >stdout.txt 2>stderr.txt";
  const int rc = std::system(cmd.c_str());
  if (err) *err = slurp(work / "stderr.txt");
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::size_t count_lines(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

}  // namespace

TEST_CASE("asperity fit writes the results directory", "[fit][cli]") {
  const FitCase c = make_fit_case("cli", 0.7e-15, 1.5, 0.1, 40);
  write_text(c.dir / "f.yaml",
             "name: small\nobjective: area_curve\nexperiments: [scene.yaml]\n"
             "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: log}}\n"
             "optimizer: {starts: 2}\nprofile: {span: 0.1, points: 3}\nerror_bars: {experiment.E: 0.1e6}\n");
  REQUIRE(asperity_in(c.dir, "fit f.yaml --quiet --threads 2") == 0);
  const fs::path out = c.dir / "results" / "fits" / "small";
  const std::string y = slurp(out / "fit.yaml");
  CHECK(y.find("stop_reason: XTOL_REACHED") != std::string::npos);
  CHECK(y.find("status: ok") != std::string::npos);
  CHECK(y.find("error_bars:") != std::string::npos);
  CHECK(y.find("key: experiment.E, shift: -100000") != std::string::npos);
  CHECK(y.find("key: experiment.E, shift: 100000") != std::string::npos);
  // Provenance: the command as typed, the fit file and the experiment's data by content.
  CHECK(y.find("command_line: \"asperity fit f.yaml --quiet --threads 2\"") != std::string::npos);
  CHECK(y.find("{role: \"fit\", path: \"f.yaml\", fnv1a64: \"" +
               asperity::io::hex16(asperity::io::fnv1a64(slurp(c.dir / "f.yaml"))) + "\"}") != std::string::npos);
  CHECK(y.find("{role: \"measured\"") != std::string::npos);
  // One CSV row per evaluation, as counted in fit.yaml.
  const auto at = y.find("\n    evaluations: ");
  REQUIRE(at != std::string::npos);
  const int n = std::stoi(y.substr(at + 18));
  CHECK(count_lines(slurp(out / "evaluations.csv")) == static_cast<std::size_t>(n) + 1);
  CHECK(count_lines(slurp(out / "profile.csv")) == 4);
  CHECK(fs::exists(out / "AQ_fit-cli_model.csv"));
  CHECK(fs::exists(out / "AQ_fit-cli_measured.csv"));
  CHECK(fs::exists(out / "fitted.csv"));
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    CHECK(fs::file_size(out / "convergence.png") > 1000);
    CHECK(fs::file_size(out / "AQ_fit-cli.png") > 1000);
    CHECK(fs::file_size(out / "profile.png") > 1000);
  }
  // A second run replaces it; a directory that is not a fit's is never replaced.
  REQUIRE(asperity_in(c.dir, "fit f.yaml --quiet --no-profile --no-error-bars") == 0);
  CHECK_FALSE(fs::exists(out / "profile.csv"));
  fs::create_directories(c.dir / "other");
  write_text(c.dir / "other" / "keep.txt", "x");
  std::string err;
  CHECK(asperity_in(c.dir, "fit f.yaml --quiet --out other", &err) == 2);
  CHECK(err.rfind("other: --out: refusing to write there", 0) == 0);
  CHECK(fs::exists(c.dir / "other" / "keep.txt"));
  fs::remove_all(c.dir);
}

TEST_CASE(
    "asperity fit certifies a multi-start optimum, and exits 1 on a mutant optimizer that stops at its first point",
    "[fit][cli][convergence]") {
  const FitCase c = make_fit_case("cli-conv", 0.7e-15, 1.5, 0.1, 40);
  const std::string head =
      "objective: area_curve\nexperiments: [scene.yaml]\n"
      "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: log}}\nprofile: false\n";
  // Three LN_BOBYQA starts on a one-basin objective: all reach it.
  write_text(c.dir / "good.yaml", head + "optimizer: {algorithm: LN_BOBYQA, starts: 3}\n");
  std::string err;
  REQUIRE(asperity_in(c.dir, "fit good.yaml --quiet --out good", &err) == 0);
  const std::string y = slurp(c.dir / "good" / "fit.yaml");
  CHECK(y.find("    converged: yes") != std::string::npos);
  CHECK(y.find("    starts: 3\n") != std::string::npos);
  CHECK(y.find("    in_best_basin: 3\n") != std::string::npos);
  CHECK(y.find("      - {start: 3, from: [") != std::string::npos);
  // The mutant: DIRECT stopped at its first lattice point (the centre), each start's polish at
  // its start. The fit is written, says so, and fails the check: exit 1, one line.
  write_text(c.dir / "mutant.yaml", head +
                                        "optimizer: {algorithm: GN_DIRECT_L, max_evaluations: 1, starts: 3, "
                                        "polish: {algorithm: LN_BOBYQA, max_evaluations: 1}}\n");
  CHECK(asperity_in(c.dir, "fit mutant.yaml --quiet --out mutant", &err) == 1);
  CHECK(err == "fit fit-cli-conv did not converge: only 1 of 3 starts reached the best objective " +
                   err.substr(err.find("objective ") + 10, err.find(" (within") - err.find("objective ") - 10) +
                   " (within 0.001 relative, or 0.001 in the scaled coordinates): no other start confirms it\n");
  const std::string m = slurp(c.dir / "mutant" / "fit.yaml");
  CHECK(m.find("    converged: no") != std::string::npos);
  CHECK(m.find("    in_best_basin: 1\n") != std::string::npos);
  // A single start is unverified: nothing confirms it, a failed check as well, said in one line;
  // optimizer.certify: false accepts it (exit 0, said unless --quiet).
  write_text(c.dir / "one.yaml", head + "optimizer: {algorithm: LN_BOBYQA}\n");
  CHECK(asperity_in(c.dir, "fit one.yaml --quiet --out one", &err) == 1);
  CHECK(err ==
        "fit fit-cli-conv is not certified: one start: nothing to compare its optimum with; set optimizer.starts "
        ">= 2 to certify it, or optimizer.certify: false to accept it unconfirmed\n");
  CHECK(slurp(c.dir / "one" / "fit.yaml").find("    converged: unverified") != std::string::npos);
  write_text(c.dir / "accepted.yaml", head + "optimizer: {algorithm: LN_BOBYQA, certify: false}\n");
  CHECK(asperity_in(c.dir, "fit accepted.yaml --quiet --out accepted", &err) == 0);
  CHECK(err.empty());
  const std::string a = slurp(c.dir / "accepted" / "fit.yaml");
  CHECK(a.find("    converged: unverified") != std::string::npos);
  CHECK(a.find("\ncertify: false") != std::string::npos);
  fs::remove_all(c.dir);
}

TEST_CASE("asperity fit on a bad fit file exits 2 naming file and line", "[fit][cli]") {
  const FitCase c = make_fit_case("clibad", 0.7e-15, 1.5, 0.1, 40);
  write_text(c.dir / "bad.yaml",
             "objective: quadratic_alpha\nexperiments: [scene.yaml]\n"
             "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15}}\n"
             "optimizer: {max_evaluations: 0}\n");
  std::string err;
  CHECK(asperity_in(c.dir, "fit bad.yaml", &err) == 2);
  CHECK(err.find("bad.yaml:4: optimizer.max_evaluations: must be >= 1") != std::string::npos);
  CHECK_FALSE(fs::exists(c.dir / "results"));
  fs::remove_all(c.dir);
}
