// The options commands share (cli/options.hpp) and the progress line (io/progress.hpp): the same
// -j/--threads everywhere, --set on sweep and fit equal to the same value in the files, --quiet
// silent, Ctrl-C in `run` exits 130 with nothing written; the thread range and NUL check of
// io/arguments.hpp that --threads and the Python module share.
#include <signal.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <thread>
#include <tuple>

#include "cli_spawn.hpp"
#include "io/arguments.hpp"
#include "io/input_error.hpp"
#include "io/progress.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;
using Catch::Contains;

namespace {
const fs::path kSource = ASPERITY_SOURCE_DIR;

// points.csv without hash (it names the experiment file relative to the campaign's folder)
// and wall_s (the last column): the values two stores must agree on.
std::string values_of(const fs::path& store) {
  std::string out;
  std::istringstream in(slurp(store / "points.csv"));
  for (std::string l; std::getline(in, l);) {
    const std::size_t a = l.find(','), b = l.find(',', a + 1);
    out += l.substr(0, a) + l.substr(b, l.rfind(',') - b) + "\n";
  }
  return out;
}
}  // namespace

TEST_CASE("threads (-j, --threads) mean the same in every command and are checked the same", "[cli][options]") {
  const fs::path w = fs::temp_directory_path();
  const std::vector<std::vector<std::string>> commands{{"run", "x.yaml"}, {"sweep", "x.yaml"},
                                                       {"fit", "x.yaml"}, {"reproduce", "x.yaml"},
                                                       {"regress"},       {"bench", "savings"}};
  for (const auto& cmd : commands) {
    for (const char* opt : {"-j", "--threads"}) {
      std::vector<std::string> args = cmd;
      args.insert(args.begin() + 1, {opt, "0"});
      const CliResult r = run_argv(w, args);
      INFO(cmd[0] << " " << opt);
      CHECK(r.status == 2);
      CHECK_THAT(r.err, Contains("--threads") && Contains("not in range 1 to 1024"));
      CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    }
  }
}

TEST_CASE("the library's thread range and NUL check, shared by --threads and the Python module", "[io][options]") {
  CHECK(io::threads_problem("1").empty());
  CHECK(io::threads_problem("1024").empty());
  CHECK(io::checked_threads("16", "threads") == 16);
  for (const char* bad : {"0", "-1", "1025", "1000000000", "99999999999999999999", "", "4x", "abc"})
    CHECK(io::threads_problem(bad) == "Value " + std::string(bad) + " not in range 1 to 1024");
  CHECK_THROWS_WITH(io::checked_threads("-1", "threads"), "threads: Value -1 not in range 1 to 1024");
  CHECK_NOTHROW(io::check_no_nul("a/b.yaml", "campaign"));
  using namespace std::string_literals;
  CHECK_THROWS_WITH(io::check_no_nul("a.yaml\0x"s, "campaign"),
                    "a.yaml\\0x: campaign: holds a NUL byte (character 7), which would end the text there");
  CHECK_THROWS_AS(io::check_no_nul("\0"s, "out"), io::InputError);
}

TEST_CASE("sweep --set equals the value in the campaign and fit --set equals it in the fit file", "[cli][options]") {
  const fs::path w = temp_path("cli_options");
  fs::remove_all(w);
  fs::create_directories(w);
  const fs::path data = kSource / "tests" / "data" / "campaign";
  // The campaign with c_min set in its own `set:` (a copy naming the fixture's scene by path).
  std::string text = slurp(data / "tiny.yaml");
  text.replace(text.find("set: {stop.time: 0.3}"), 21, "set: {stop.time: 0.3, model.c_min: 0.02}");
  text.replace(text.find("scenes: [tiny_scene.yaml]"), 25, "scenes: [" + (data / "tiny_scene.yaml").string() + "]");
  const fs::path edited = write_text(w / "tiny_cmin.yaml", text);
  REQUIRE(
      run_argv(w, {"sweep", (data / "tiny.yaml").string(), "--out", "a", "-j", "1", "-q", "--set", "model.c_min=0.02"})
          .status == 0);
  REQUIRE(run_argv(w, {"sweep", edited.string(), "--out", "b", "-j", "1", "-q"}).status == 0);
  CHECK(values_of(w / "a") == values_of(w / "b"));
  REQUIRE(run_argv(w, {"sweep", (data / "tiny.yaml").string(), "--out", "d", "-j", "1", "-q"}).status == 0);
  CHECK(values_of(w / "a") != values_of(w / "d"));  // and the value did change the runs
  // A bad --set is one line naming it, before any point runs.
  const CliResult bad = run_argv(w, {"sweep", (data / "tiny.yaml").string(), "--out", "c", "--set", "model.c_min=2"});
  CHECK(bad.status == 2);
  CHECK_THAT(bad.err, Contains("--set model.c_min=2") && Contains("model.c_min"));
  CHECK_FALSE(fs::exists(w / "c"));

  const std::string scene = (kSource / "tests" / "data" / "scene" / "small_scene.yaml").string();
  write_text(w / "f1.yaml", "name: f1\nobjective: area_curve\nexperiments: [" + scene +
                                "]\nparameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15, scale: "
                                "log}}\noptimizer: {certify: false}\n");
  write_text(w / "f2.yaml", "name: f2\nobjective: area_curve\nexperiments: [{scene: " + scene +
                                ", set: {model.eta: 60}}]\nparameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: "
                                "1e-15, scale: log}}\noptimizer: {certify: false}\n");
  REQUIRE(
      run_argv(w, {"fit", "f1.yaml", "--out", "o1", "-j", "1", "-q", "--no-profile", "--set", "model.eta=60"}).status ==
      0);
  REQUIRE(run_argv(w, {"fit", "f2.yaml", "--out", "o2", "-j", "1", "-q", "--no-profile"}).status == 0);
  const auto best = [](const std::string& y) {
    const auto at = y.find("\"model.alpha_b\": {value: ");
    return at == std::string::npos ? std::string("none") : y.substr(at, y.find(',', at) - at);
  };
  CHECK(best(slurp(w / "o1" / "fit.yaml")) == best(slurp(w / "o2" / "fit.yaml")));
  CHECK(best(slurp(w / "o1" / "fit.yaml")) != "none");
  fs::remove_all(w);
}

TEST_CASE("quiet (-q) prints nothing on success", "[cli][options]") {
  const fs::path w = temp_path("cli_quiet");
  fs::remove_all(w);
  fs::create_directories(w);
  const std::vector<std::vector<std::string>> commands{
      {"run", (kSource / "tests" / "data" / "scene" / "small_scene.yaml").string(), "--out", "r", "-q"},
      {"sweep", (kSource / "tests" / "data" / "campaign" / "tiny.yaml").string(), "--out", "s", "-q", "-j", "1"}};
  for (const auto& args : commands) {
    const CliResult r = run_argv(w, args);
    CHECK(r.status == 0);
    CHECK(r.out.empty());
    CHECK(r.err.empty());
  }
  fs::remove_all(w);
}

TEST_CASE("Ctrl-C stops a run within a fraction of a second, exit 130, nothing written", "[cli][options]") {
  const fs::path w = temp_path("cli_sigint");
  fs::remove_all(w);
  fs::create_directories(w);
  // About 10 s uninterrupted: the reference solver on 1,201 junctions for 0.3 s simulated.
  std::vector<std::string> all{ASPERITY_BINARY,
                               "run",
                               (kSource / "scenes" / "paper" / "P4.00N.yaml").string(),
                               "--out",
                               (w / "r").string(),
                               "--set",
                               "solver.method=reference",
                               "--set",
                               "stop.time=0.3",
                               "-j",
                               "1"};
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) == 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  const auto t0 = std::chrono::steady_clock::now();
  ::kill(pid, SIGINT);
  int st = 0;
  while (waitpid(pid, &st, 0) < 0) {
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  CHECK(WIFEXITED(st));
  CHECK(WEXITSTATUS(st) == 130);
  CHECK(s < 1.0);
  CHECK_FALSE(fs::exists(w / "r"));
  fs::remove_all(w);
}

TEST_CASE("the progress line's ETA is elapsed x remaining / done", "[io][progress]") {
  CHECK(io::eta_seconds(10, 25, 100) == 30);
  CHECK(std::isnan(io::eta_seconds(10, 0, 100)));
  CHECK(io::eta_seconds(10, 100, 100) == 0);
  CHECK(io::duration_text(45) == "45s");
  CHECK(io::duration_text(187) == "3m07s");
  CHECK(io::duration_text(7500) == "2h05m");
  const io::ProgressLine p("fit", "evaluations", 60, true);
  CHECK(p.text(15, 30, "best 1.2e-3") == "fit: 15/60 evaluations, 30s elapsed, ETA 1m30s, best 1.2e-3");
  const io::ProgressLine q("run", "s simulated", 10, true);
  CHECK(q.text(2.5, 4, "") == "run: 2.5/10 s simulated, 4s elapsed, ETA 12s");
}

TEST_CASE("sweep --sync-every and --sync-seconds are checked in one line", "[cli][options]") {
  const fs::path w = fs::temp_directory_path();
  for (const auto& [opt, value, range] :
       {std::tuple<const char*, const char*, const char*>{"--sync-every", "0", "1 to 1000000000"},
        {"--sync-seconds", "-1", "0 to 86400"}}) {
    const CliResult r = run_argv(w, {"sweep", "x.yaml", opt, value});
    INFO(opt);
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Contains(opt) && Contains(std::string("not in range ") + range));
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}
