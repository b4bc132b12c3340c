// Regression runs: tolerances from the tightened twin, comparison, and drift detection end to end.
#include <unistd.h>

#include <sys/wait.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/input_error.hpp"
#include "regress/regress.hpp"
#include "scene/load.hpp"
#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;

TEST_CASE("regress: tolerance is 10x the tightening change, floored at 10x the solver tolerance", "[regress]") {
  RegressResult r;
  r.name = "x";
  r.solver_rel_floor = 1e-8;
  r.values = {{"Q_s", 2.0}, {"ss_drop", 0.5}, {"ss_cycles", 5}, {"ss_period", std::nan("")}};
  r.tight = {{"Q_s", 2.0 + 1e-6}, {"ss_drop", 0.5}, {"ss_cycles", 4}, {"ss_period", std::nan("")}};
  const Golden g = bless({r}, {});
  CHECK_THAT(g.entries.at("x").at("Q_s").tolerance, Catch::Matchers::WithinRel(1e-5, 1e-9));
  CHECK_THAT(g.entries.at("x").at("ss_drop").tolerance, Catch::Matchers::WithinRel(0.5e-8, 1e-12));
  CHECK(g.entries.at("x").at("ss_cycles").tolerance == 1.0);
  // Round trip through the golden file, then compare: inside passes, outside drifts, NaN = NaN.
  const fs::path f = asperity::testing::temp_path("asperity_test_golden", ".yaml");
  std::ofstream(f) << golden_to_yaml(g);
  const Golden back = load_golden(f);
  CHECK(back.entries.at("x").at("Q_s").value == 2.0);
  RegressResult now = r;
  now.values["Q_s"] = 2.0 + 0.9e-5;
  now.values["ss_drop"] = 0.5 + 1e-8;
  int drifted = 0;
  for (const auto& d : compare(back, {now})) {
    drifted += d.ok ? 0 : 1;
    if (d.observable == "ss_drop") CHECK_FALSE(d.ok);
    if (d.observable == "Q_s") CHECK(d.ok);
    if (d.observable == "ss_period") CHECK(d.ok);
  }
  CHECK(drifted == 1);
  fs::remove(f);
}

TEST_CASE("asperity regress passes on the committed golden results and catches an injected drift",
          "[regress][cli][heavy]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const fs::path work = asperity::testing::temp_path("asperity_test_regress");
  fs::remove_all(work);
  fs::create_directories(work);
  auto run = [&](const std::string& args) {
    const std::string cmd = "cd '" + src.string() + "' && '" + ASPERITY_BINARY + "' regress " + args + " >'" +
                            (work / "out.txt").string() + "' 2>&1";
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  CHECK(run("") == 0);
  // The same suite with η changed by 0.5 % in one entry must drift, naming that entry.
  std::ifstream in(src / "scenes/regression/suite.yaml");
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const std::string from = "../paper/P0.98N.yaml, set: [stop.cycles=5]";
  REQUIRE(text.find(from) != std::string::npos);
  text.replace(text.find(from), from.size(),
               "'" + (src / "scenes/paper/P0.98N.yaml").string() + "', set: [stop.cycles=5, model.eta=100.5]");
  // Other scene paths are relative to the suite: keep the copy beside the original.
  const fs::path drift =
      src / "scenes/regression" / asperity::testing::temp_path(".drift_test_suite", ".yaml").filename();
  std::ofstream(drift) << text;
  const int rc = run("--suite '" + drift.string() + "'");
  fs::remove(drift);
  std::ifstream out(work / "out.txt");
  std::stringstream o;
  o << out.rdbuf();
  INFO("regress output: " << o.str());
  CHECK(rc == 1);
  CHECK(o.str().find("P0.98N_stick_slip") != std::string::npos);
  CHECK(o.str().find("DRIFT") != std::string::npos);
  CHECK(o.str().find("P6.40N_stick_slip") == std::string::npos);  // untouched entries still pass
  fs::remove_all(work);
}

// A golden file is data someone may edit: a second value for one entry or observable (YAML keeps
// the last) and an observable no run computes (never compared) would pass silently.
TEST_CASE("a golden file with a duplicate entry or observable, or an unknown observable, is refused at its line",
          "[regress]") {
  const fs::path src(ASPERITY_SOURCE_DIR);
  const std::string golden = asperity::testing::slurp(src / "results/regression/golden.yaml");
  const std::string entry = "  P0.98N_linear:\n";
  REQUIRE(golden.find(entry) != std::string::npos);
  const auto line_at = [](const std::string& text, std::size_t pos) {
    return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
  };
  const std::string forged_entry = entry + "    Q_s: {value: 1, tolerance: 1e9}\n";
  struct Forgery {
    std::string text, key, message;
    int line;
  };
  std::vector<Forgery> forgeries;
  {  // a forged copy of an entry before the real one
    std::string t = golden;
    t.insert(t.find("entries:\n") + 9, forged_entry);
    forgeries.push_back({t, "entries.P0.98N_linear", "duplicate key (first given at line", line_at(t, t.rfind(entry))});
  }
  {  // a forged observable before the real one, inside the entry
    std::string t = golden;
    t.insert(t.find(entry) + entry.size(), "    Q_s: {value: 1, tolerance: 1e9}\n");
    const std::size_t real = t.find("    Q_s: ", t.find(entry) + entry.size() + 1);
    REQUIRE(real != std::string::npos);
    forgeries.push_back({t, "entries.P0.98N_linear.Q_s", "duplicate key (first given at line", line_at(t, real)});
  }
  {  // an observable nothing computes
    std::string t = golden;
    t.insert(t.find(entry) + entry.size(), "    Q_static: {value: 1, tolerance: 0}\n");
    forgeries.push_back({t, "entries.P0.98N_linear.Q_static", "unknown key 'Q_static'", line_at(t, t.find(entry)) + 1});
  }
  const fs::path f = asperity::testing::temp_path("asperity_test_golden_forged", ".yaml");
  for (const Forgery& g : forgeries) {
    INFO(g.key);
    std::ofstream(f) << g.text;
    try {
      (void)load_golden(f);
      FAIL("load_golden accepted it");
    } catch (const io::InputError& e) {
      CHECK(e.file == f.string());
      CHECK(e.line == g.line);
      CHECK(e.key == g.key);
      CHECK(e.message.rfind(g.message, 0) == 0);
    }
    // The command: exit 2, one line naming file, line and key, before any run.
    const fs::path err = asperity::testing::temp_path("asperity_test_golden_err", ".txt");
    const std::string cmd = "cd '" + src.string() + "' && '" + ASPERITY_BINARY + "' regress --golden '" + f.string() +
                            "' >/dev/null 2>'" + err.string() + "'";
    const int rc = std::system(cmd.c_str());
    const std::string text = asperity::testing::slurp(err);
    INFO(text);
    CHECK((WIFEXITED(rc) ? WEXITSTATUS(rc) : -1) == 2);
    CHECK(text.rfind(f.string() + ":" + std::to_string(g.line) + ":", 0) == 0);
    CHECK(text.find(": " + g.key + ": ") != std::string::npos);
    CHECK(std::count(text.begin(), text.end(), '\n') == 1);
    fs::remove(err);
  }
  fs::remove(f);
}
