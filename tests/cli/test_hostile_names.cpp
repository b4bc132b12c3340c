// Hostile names and paths through every command that draws (run --plot, reproduce, fit, sweep +
// plot with its default output, --out and --where): text from inputs is data, never code. Each
// payload would create a file named PWNED if gnuplot or a shell ran it; none may appear, the
// outputs must exist, and names must come back intact from table.csv / fitted.csv. Names with
// control characters are refused at load with "file:line: key:" and exit 2, writing nothing.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "campaign/store.hpp"
#include "cli_spawn.hpp"
#include "report/gnuplot.hpp"
#include "scene/load.hpp"

namespace fs = std::filesystem;
using asperity::testing::run_argv;
using asperity::testing::slurp;
using asperity::testing::snapshot;

namespace {

const fs::path kExp = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "scene" / "exp_small";

// Each would run `touch PWNED` if it reached gnuplot (system(), backquotes, `!` at a line
// start) or a shell ($( ), backquotes, ';') as code.
const std::vector<std::string> kHostile = {
    "x'.system(\"touch PWNED\").'",
    "x\".system(\"touch PWNED\").\"",
    "`touch PWNED`",
    "$(touch PWNED)",
    "a; system(\"touch PWNED\"); #",
    "!touch PWNED",
    "@x \\ name with spaces '' \"\" \\",
    "Ωμέγα ✓ 摩擦 'q' `touch PWNED`",
    std::string(300, 'L') + "'.system(\"touch PWNED\").'",
};

using asperity::testing::write_text;

// "<prefix><i><suffix>", built by appending: GCC 12 warns falsely (-Wrestrict) on "lit" + std::string&&.
std::string numbered(const char* prefix, std::size_t i, const char* suffix) {
  std::string s(prefix);
  s += std::to_string(i);
  s += suffix;
  return s;
}

// A fresh folder with the five-junction fixture experiment under each hostile name:
// e<i>.yaml (experiment) and s<i>.yaml (a short scene).
fs::path hostile_case(const std::string& tag) {
  const fs::path w = asperity::testing::temp_path("asperity-hostile-" + tag);
  fs::remove_all(w);
  fs::create_directories(w);
  fs::copy_file(kExp / "junctions.csv", w / "junctions.csv");
  fs::copy_file(kExp / "measured.csv", w / "measured.csv");
  for (std::size_t i = 0; i < kHostile.size(); ++i) {
    write_text(w / (numbered("e", i, ".yaml")),
               "# hostile name on line 2\nname: " + asperity::io::yaml_quoted(kHostile[i]) +
                   "\nmass: 0.1\nk_L: 9200\nv: 1.0e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 0.23e6\n"
                   "junctions: junctions.csv\nmeasured: measured.csv\n");
    write_text(w / (numbered("s", i, ".yaml")),
               numbered("experiment: e", i, ".yaml\n") +
                   "solver: {method: event, tolerance: 1e-8}\nstop: {time: 0.3}\noutput: {series: [t, Q, A]}\n");
  }
  return w;
}

// Files named PWNED anywhere under `dir` (what an executed payload leaves).
std::vector<std::string> pwned_files(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename() == "PWNED") found.push_back(e.path().string());
  return found;
}

std::vector<std::string> csv_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::multiset<std::string> hostile_set() { return {kHostile.begin(), kHostile.end()}; }

bool drawn(const fs::path& png) { return !asperity::io::gnuplot_available() || fs::file_size(png) > 1000; }

}  // namespace

TEST_CASE("gnuplot_quote: gnuplot reads every byte back as written, control characters as '?'", "[report][hostile]") {
  if (!asperity::io::gnuplot_available()) {
    WARN("gnuplot not installed: nothing to check");
    return;
  }
  const fs::path w = asperity::testing::temp_path("asperity-gpquote");
  fs::remove_all(w);
  fs::create_directories(w);
  std::string all;  // every printable byte, and the corpus
  for (int c = 0x20; c <= 0xff; ++c)
    if (c != 0x7f) all += static_cast<char>(c);
  std::vector<std::string> texts = kHostile;
  texts.push_back(all);
  texts.push_back(
      "a\nb\tc\rd\x01"
      "e\x7f"
      "f\\");
  std::ostringstream gp;
  gp << "set print 'got.txt'\n";
  for (const auto& t : texts) gp << "s = " << asperity::gnuplot_quote(t) << "\nprint s\n";
  asperity::io::run_gnuplot(w, gp.str());
  std::string want;
  for (std::size_t k = 0; k + 1 < texts.size(); ++k) want += texts[k] + "\n";
  want += "a?b?c?d?e?f\\\n";
  CHECK(slurp(w / "got.txt") == want);
  CHECK(pwned_files(w).empty());
  fs::remove_all(w);
}

TEST_CASE("hostile names and paths through run --plot, reproduce, fit, sweep and plot stay data", "[cli][hostile]") {
  const fs::path w = hostile_case("draw");
  const std::size_t n = kHostile.size();

  // run --plot, into a hostile --out folder.
  for (std::size_t i = 0; i < n; ++i) {
    const std::string out = "run '$(touch PWNED)\"`touch PWNED`" + std::to_string(i);
    const auto r = run_argv(w, {"run", numbered("s", i, ".yaml"), "--out", out, "--plot", "--quiet"});
    REQUIRE(r.status == 0);
    CHECK(YAML::LoadFile((w / out / "summary.yaml").string())["experiment"].as<std::string>() == kHostile[i]);
    CHECK(drawn(w / out / "plot.png"));
  }

  // reproduce: every name in Figure 4's keys and in table.csv, one row each.
  {
    std::vector<std::string> args{"reproduce"};
    for (std::size_t i = 0; i < n; ++i) args.push_back(numbered("s", i, ".yaml"));
    const std::string out = "rep'.system(\"touch PWNED\").'";
    args.insert(args.end(), {"--out", out, "--no-claims", "--quiet", "-j", "2"});
    const auto r = run_argv(w, args);
    INFO(r.err);
    REQUIRE(r.status == 0);
    CHECK(drawn(w / out / "fig3_Q_A_t.png"));
    CHECK(drawn(w / out / "fig4_A_Q.png"));
    const auto lines = csv_lines(slurp(w / out / "table.csv"));
    REQUIRE(lines.size() == n + 1);
    std::multiset<std::string> names;
    for (std::size_t k = 1; k < lines.size(); ++k) {
      const auto f = asperity::io::csv_split(lines[k]);
      CHECK(f.size() == asperity::io::csv_split(lines[0]).size());
      names.insert(f.at(0));
    }
    CHECK(names == hostile_set());
  }

  // fit, one separate fit per hostile experiment: titles, file names, fitted.csv.
  {
    std::string fit = "name: hostile\nobjective: quadratic_alpha\nseparate: true\nexperiments: [";
    for (std::size_t i = 0; i < n; ++i) fit += (i ? ", s" : "s") + std::to_string(i) + ".yaml";
    fit +=
        "]\nparameters:\n  model.alpha_b: {lo: 0.1e-15, hi: 5.0e-15, start: 0.725e-15, scale: log}\n"
        "optimizer: {algorithm: LN_BOBYQA, max_evaluations: 3, certify: false}\n";
    write_text(w / "fit.yaml", fit);
    const std::string out = "fit \"'$(touch PWNED)";
    const auto r = run_argv(w, {"fit", "fit.yaml", "--out", out, "--no-profile", "--no-error-bars", "--quiet"});
    INFO(r.err);
    REQUIRE(r.status != 2);
    const auto lines = csv_lines(slurp(w / out / "fitted.csv"));
    REQUIRE(lines.size() == n + 1);
    std::multiset<std::string> names;
    for (std::size_t k = 1; k < lines.size(); ++k) names.insert(asperity::io::csv_split(lines[k]).at(1));
    CHECK(names == hostile_set());
    // One folder per fit, each with its A(Q) plot: no two names share files.
    std::size_t pngs = 0, folders = 0;
    for (const auto& e : fs::directory_iterator(w / out))
      if (e.is_directory()) {
        ++folders;
        for (const auto& f : fs::directory_iterator(e.path()))
          if (f.path().extension() == ".png" && f.path().filename().string().rfind("AQ_", 0) == 0) {
            ++pngs;
            CHECK(drawn(f.path()));
          }
      }
    CHECK(folders == n);
    CHECK(drawn(w / out / "fitted.png"));  // fitted values against the load, all fits
    if (asperity::io::gnuplot_available()) CHECK(pngs == n);
  }

  // A campaign named with a quote payload (its store folder), over all hostile experiments;
  // plot with the default output, a hostile --out and --where experiment=<each name>.
  {
    std::string camp = "name: " + asperity::io::yaml_quoted(kHostile[0]) + "\nscenes: [";
    for (std::size_t i = 0; i < n; ++i) camp += (i ? ", s" : "s") + std::to_string(i) + ".yaml";
    camp += "]\nset: {stop.time: 0.3}\naxes:\n  model.eta: [0, 100]\n  model.epsilon: [0.5, 0.9]\n";
    write_text(w / "camp.yaml", camp);
    const auto s = run_argv(w, {"sweep", "camp.yaml", "--quiet", "-j", "2"});
    INFO(s.err);
    REQUIRE(s.status == 0);
    const fs::path store = fs::path("results") / kHostile[0];
    REQUIRE(fs::exists(w / store / "points.csv"));
    const std::vector<std::string> axes{"--x", "model.eta", "--y", "model.epsilon", "--z", "Q_s"};
    auto plot = [&](std::vector<std::string> extra) {
      std::vector<std::string> args{"plot", store.string()};
      args.insert(args.end(), axes.begin(), axes.end());
      args.insert(args.end(), extra.begin(), extra.end());
      return run_argv(w, args);
    };
    const auto d = plot({"--where", "experiment=" + kHostile[1], "--quiet"});
    INFO(d.err);
    CHECK(d.status == 0);
    CHECK(drawn(w / store / "heatmap_Q_s_over_model_eta_model_epsilon.png"));
    for (std::size_t i = 0; i < n; ++i) {
      const std::string png = "pic'.system(\"touch PWNED\").'`touch PWNED`$(touch PWNED)" + std::to_string(i) + ".png";
      const auto r = plot({"--where", "experiment=" + kHostile[i], "--out", png, "--quiet"});
      INFO(kHostile[i] << ": " << r.err);
      CHECK(r.status == 0);
      CHECK(drawn(w / png));
    }
  }

  CHECK(pwned_files(w).empty());
  fs::remove_all(w);
}

TEST_CASE("names with control characters are refused at load with file:line: key: and nothing written",
          "[cli][hostile]") {
  const fs::path w = hostile_case("ctl");
  write_text(w / "e_nl.yaml",
             "# a newline in the name\nname: \"a\\nsystem(\\\"touch PWNED\\\")\"\nmass: 0.1\nk_L: 9200\nv: 1.0e-4\n"
             "E: 1.6e6\nnu: 0.5\nsigma_exp: 0.23e6\njunctions: junctions.csv\nmeasured: measured.csv\n");
  write_text(w / "s_nl.yaml", "experiment: e_nl.yaml\nstop: {time: 0.3}\n");
  write_text(w / "fit_nl.yaml",
             "objective: quadratic_alpha\nexperiments: [s_nl.yaml]\n"
             "parameters: {model.alpha_b: {lo: 1e-16, hi: 5e-15, start: 1e-15}}\n");
  write_text(w / "camp_tab.yaml", "name: \"c\\td\"\nscenes: [s0.yaml]\naxes: {model.eta: [0, 100]}\n");
  write_text(w / "camp_grid.yaml",
             "name: cg\nscenes: [s0.yaml]\ngrids:\n  - name: \"g\\rh\"\n    axes: {model.eta: [0, 100]}\n");
  write_text(w / "camp_exp.yaml", "name: ce\nscenes: [s_nl.yaml]\naxes: {model.eta: [0, 100]}\n");
  const auto before = snapshot(w);

  const std::string exp_prefix = "e_nl.yaml:2: name: must not hold control characters";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"run", "s_nl.yaml", "--out", "o1", "--plot"}, exp_prefix},
      {{"reproduce", "s_nl.yaml", "--out", "o2", "--no-claims"}, exp_prefix},
      {{"fit", "fit_nl.yaml", "--out", "o3"}, exp_prefix},
      {{"sweep", "camp_exp.yaml", "--out", "o4"}, exp_prefix},
      {{"sweep", "camp_tab.yaml"},
       "camp_tab.yaml:1: name: must be a plain folder name (no '/', no control characters)"},
      {{"sweep", "camp_grid.yaml"}, "camp_grid.yaml:4: grids[0].name: must not hold control characters"},
  };
  for (const auto& [args, prefix] : cases) {
    const auto r = run_argv(w, args);
    INFO(args.front() << " " << args.at(1) << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.rfind(prefix, 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);  // one line
  }
  CHECK(snapshot(w) == before);
  fs::remove_all(w);
}
