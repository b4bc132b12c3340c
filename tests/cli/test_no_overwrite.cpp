// No command overwrites a file or folder it did not create: run, fit, generate, reproduce, merge
// and plot refuse (exit 2, one line "PATH: --out: ...") to write into a user's folder or over a user's
// file, which stay byte-identical; they replace what they wrote themselves (the .asperity
// marker, or a PNG tagged by render_png). Also: reproduce leaves no stale REPORT.md, and the fit
// outputs of experiments named "x y" and "x_y" do not collide.
#include <yaml-cpp/yaml.h>

#include <sys/stat.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "cli_spawn.hpp"
#include "report/gnuplot.hpp"
#include "synthetic_support.hpp"

namespace fs = std::filesystem;
using asperity::testing::CliResult;
using asperity::testing::run_argv;
using asperity::testing::slurp;
using asperity::testing::snapshot;

namespace {

const fs::path kExp = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "scene" / "exp_small";

using asperity::testing::write_text;

std::string experiment_yaml(const std::string& name, double mass) {
  return "name: \"" + name + "\"\nmass: " + std::to_string(mass) +
         "\nk_L: 9200\nv: 1.0e-4\nE: 1.6e6\nnu: 0.5\nsigma_exp: 0.23e6\njunctions: junctions.csv\nmeasured: "
         "measured.csv\n";
}

// A working folder with two short scenes (s1: experiment "x y", s2: "x_y", other mass), a fit of
// both separately, a campaign, and a user's folder `user/` holding files of every name a
// command writes.
fs::path make_case(const std::string& tag) {
  const fs::path w = asperity::testing::temp_path("asperity-nooverwrite-" + tag);
  fs::remove_all(w);
  fs::create_directories(w);
  fs::copy_file(kExp / "junctions.csv", w / "junctions.csv");
  fs::copy_file(kExp / "measured.csv", w / "measured.csv");
  write_text(w / "e1.yaml", experiment_yaml("x y", 0.1));
  write_text(w / "e2.yaml", experiment_yaml("x_y", 0.12));
  for (const char* k : {"1", "2"})
    write_text(
        w / (std::string("s") + k + ".yaml"),
        std::string("experiment: e") + k + ".yaml\nsolver: {method: event, tolerance: 1e-8}\nstop: {time: 0.3}\n");
  write_text(w / "fit.yaml",
             "name: xy\nobjective: quadratic_alpha\nseparate: true\nexperiments: [s1.yaml, s2.yaml]\n"
             "parameters:\n  model.alpha_b: {lo: 0.1e-15, hi: 5.0e-15, start: 0.725e-15, scale: log}\n"
             "optimizer: {algorithm: LN_BOBYQA, max_evaluations: 3, certify: false}\n");
  write_text(w / "camp.yaml",
             "name: camp\nscenes: [s1.yaml]\naxes:\n  model.eta: [0, 100]\n  model.epsilon: [0.5, 0.9]\n");
  for (const char* f : {"thesis.tex", "table.csv", "points.csv", "summary.yaml", "scene.yaml", "REPORT.md"})
    write_text(w / "user" / f, std::string("the user's own ") + f + "\n");
  write_text(w / "user" / "fit.yaml", "# the user's fit file\nname: mine\n");
  return w;
}

// The command is refused with exit 2 and one line naming the folder and --out, and nothing under
// `w` changed.
void check_refused(const fs::path& w, const std::vector<std::string>& args, const std::string& prefix) {
  const auto before = snapshot(w);
  const CliResult r = run_argv(w, args);
  INFO(args.front() << ": " << r.err);
  CHECK(r.status == 2);
  CHECK(r.err.rfind(prefix, 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(snapshot(w) == before);
}

const std::vector<std::string> kPlotAxes{"--x", "model.eta", "--y", "model.epsilon", "--z", "Q_s", "--quiet"};

std::vector<std::string> plot_args(const std::string& out) {
  std::vector<std::string> a{"plot", "results/camp"};
  a.insert(a.end(), kPlotAxes.begin(), kPlotAxes.end());
  if (!out.empty()) a.insert(a.end(), {"--out", out});
  return a;
}

}  // namespace

TEST_CASE("no command writes into a folder it did not create, and each replaces its own", "[cli][overwrite]") {
  const fs::path w = make_case("dirs");
  const std::string refused = "user: --out: refusing to write there: it is not empty and was not written by asperity ";
  check_refused(w, {"run", "s1.yaml", "--out", "user", "--quiet"}, refused + "run");
  check_refused(w, {"fit", "fit.yaml", "--out", "user", "--quiet", "--no-profile", "--no-error-bars"}, refused + "fit");
  check_refused(w, {"reproduce", "s1.yaml", "--out", "user", "--quiet", "--no-claims"}, refused + "reproduce");

  // Each command's own folder is replaced (run, fit) or written again (reproduce); another
  // command's folder is not its own.
  for (int k = 0; k < 2; ++k) {
    CHECK(run_argv(w, {"run", "s1.yaml", "--out", "r", "--quiet"}).status == 0);
    CHECK(run_argv(w, {"fit", "fit.yaml", "--out", "f", "--quiet", "--no-profile", "--no-error-bars"}).status != 2);
    CHECK(run_argv(w, {"reproduce", "s1.yaml", "--out", "p", "--quiet", "--no-claims"}).status == 0);
  }
  CHECK(slurp(w / "r" / ".asperity").rfind("created by asperity run\nfiles v2\n", 0) == 0);
  CHECK(slurp(w / "f" / ".asperity").rfind("created by asperity fit\nfiles v2\n", 0) == 0);
  CHECK(slurp(w / "p" / ".asperity") == "created by asperity reproduce\n");
  check_refused(w, {"fit", "fit.yaml", "--out", "r", "--quiet"}, "r: --out: refusing to write there");
  check_refused(w, {"run", "s1.yaml", "--out", "p", "--quiet"}, "p: --out: refusing to write there");
  // An empty folder is fine.
  fs::create_directories(w / "empty");
  CHECK(run_argv(w, {"run", "s1.yaml", "--out", "empty", "--quiet"}).status == 0);
  CHECK(fs::exists(w / "empty" / "summary.yaml"));
  fs::remove_all(w);
}

TEST_CASE("a rerun of run or fit keeps the user's files; a folder that only looks like theirs is refused",
          "[cli][overwrite]") {
  const fs::path w = make_case("rerun");
  const std::vector<std::string> fit = {"fit", "fit.yaml", "--out", "f", "--quiet", "--no-profile", "--no-error-bars"};
  REQUIRE(run_argv(w, {"run", "s1.yaml", "--out", "r", "--quiet"}).status == 0);
  REQUIRE(run_argv(w, fit).status != 2);
  write_text(w / "r" / "notes.txt", "my notes on this run\n");
  write_text(w / "f" / "notes.txt", "my notes on this fit\n");
  fs::create_directories(w / "f" / "drafts");
  write_text(w / "f" / "drafts" / "paper.tex", "draft\n");
  // Rerun both: the user's files stay, byte for byte; the results are there again.
  REQUIRE(run_argv(w, {"run", "s1.yaml", "--out", "r", "--quiet", "--set", "model.eta=50"}).status == 0);
  REQUIRE(run_argv(w, fit).status != 2);
  CHECK(slurp(w / "r" / "notes.txt") == "my notes on this run\n");
  CHECK(slurp(w / "f" / "notes.txt") == "my notes on this fit\n");
  CHECK(slurp(w / "f" / "drafts" / "paper.tex") == "draft\n");
  CHECK(slurp(w / "r" / "scene.yaml").find("eta: 50") != std::string::npos);
  CHECK(fs::exists(w / "f" / "fit.yaml"));
  CHECK(fs::exists(w / "f" / "journal.csv"));  // the journal stays where it was
  // An output the user edited is not replaced: refused, naming it, nothing changed.
  write_text(w / "r" / "scene.yaml", slurp(w / "r" / "scene.yaml") + "# my edit\n");
  check_refused(w, {"run", "s1.yaml", "--out", "r", "--quiet"},
                (w / "r" / "scene.yaml").string() + ": --out: refusing to replace it");
  // A project folder holding a copied fit.yaml, or a copied marker without a file list: refused.
  fs::create_directories(w / "project");
  fs::copy_file(w / "f" / "fit.yaml", w / "project" / "fit.yaml");
  write_text(w / "project" / "analysis.py", "print('mine')\n");
  check_refused(w, {"fit", "fit.yaml", "--out", "project", "--quiet"}, "project: --out: refusing to write there");
  write_text(w / "project" / ".asperity", "created by asperity fit\n");
  check_refused(w, {"fit", "fit.yaml", "--out", "project", "--quiet"}, "project: --out: refusing to write there");
  check_refused(w, {"run", "s1.yaml", "--out", "project", "--quiet"}, "project: --out: refusing to write there");
  fs::remove_all(w);
}

TEST_CASE("reproduce leaves no stale REPORT.md and refuses scenes whose run folders collide", "[cli][overwrite]") {
  const fs::path w = make_case("report");
  REQUIRE(run_argv(w, {"reproduce", "s1.yaml", "--out", "p", "--quiet", "--no-claims"}).status == 0);
  write_text(w / "p" / "REPORT.md", "# verdicts of another run\n");
  REQUIRE(run_argv(w, {"reproduce", "s1.yaml", "--out", "p", "--quiet", "--no-claims"}).status == 0);
  CHECK_FALSE(fs::exists(w / "p" / "REPORT.md"));
  // Two scenes named s1.yaml in different folders would share p/s1/.
  write_text(w / "other" / "s1.yaml", "experiment: ../e2.yaml\nstop: {time: 0.3}\n");
  check_refused(w, {"reproduce", "s1.yaml", "other/s1.yaml", "--out", "q", "--quiet", "--no-claims"},
                "other/s1.yaml: two scenes share the file name s1.yaml");
  fs::remove_all(w);
}

TEST_CASE("merge --out and sweep --out only into a new or empty folder or a store", "[cli][overwrite][campaign]") {
  const fs::path w = make_case("merge");
  REQUIRE(run_argv(w, {"sweep", "camp.yaml", "--quiet", "-j", "1"}).status == 0);
  check_refused(w, {"merge", "results/camp", "--out", "user", "--quiet"},
                "user: --out: refusing to write there: it is not empty and was not written by asperity merge");
  fs::create_directories(w / "m_empty");
  CHECK(run_argv(w, {"merge", "results/camp", "--out", "m_empty", "--quiet"}).status == 0);
  CHECK(slurp(w / "m_empty" / "points.csv") == slurp(w / "results" / "camp" / "points.csv"));
  CHECK(run_argv(w, {"merge", "results/camp", "--out", "m_new", "--quiet"}).status == 0);
  CHECK(fs::exists(w / "m_new" / "points.csv"));
  // A sweep resumes a store (here the merged one: nothing left to run), never a user's folder.
  CHECK(run_argv(w, {"sweep", "camp.yaml", "--out", "m_new", "--quiet"}).status == 0);
  check_refused(w, {"sweep", "camp.yaml", "--out", "user", "--quiet"},
                "user: --out: refusing to write there: it is not empty and was not written by asperity sweep");
  fs::remove_all(w);
}

TEST_CASE("plot --out writes only figure files (.png, .svg, .pdf) and replaces only those it drew",
          "[cli][overwrite][campaign]") {
  const fs::path w = make_case("plot");
  REQUIRE(run_argv(w, {"sweep", "camp.yaml", "--quiet", "-j", "1"}).status == 0);
  check_refused(w, plot_args("user/thesis.tex"), "user/thesis.tex: --out: must name a .png, .svg or .pdf file");
  check_refused(w, plot_args("new.tex"), "new.tex: --out: must name a .png, .svg or .pdf file");
  if (!asperity::io::gnuplot_available()) {
    WARN("gnuplot not installed: the PNG cases are not checked");
    fs::remove_all(w);
    return;
  }
  // A PNG drawn by gnuplot directly (not by asperity) is the user's.
  asperity::io::run_gnuplot(w / "user", "set terminal pngcairo size 200,100\nset output 'photo.png'\nplot x\n");
  REQUIRE(fs::file_size(w / "user" / "photo.png") > 100);
  CHECK_FALSE(asperity::png_is_ours(w / "user" / "photo.png"));
  check_refused(w, plot_args("user/photo.png"),
                "user/photo.png: --out: refusing to replace a file asperity did not write");
  // Inside the store (asperity's folder) an untagged PNG is a heat map from before the tag.
  fs::copy_file(w / "user" / "photo.png", w / "results" / "camp" / "legacy.png");
  CHECK(run_argv(w, plot_args("results/camp/legacy.png")).status == 0);
  CHECK(asperity::png_is_ours(w / "results" / "camp" / "legacy.png"));
  write_text(w / "results" / "camp" / "notes.png", "not a PNG\n");
  check_refused(w, plot_args("results/camp/notes.png"), "results/camp/notes.png: --out: refusing to replace");
  // Its own PNG it replaces, and the default heat map in the store too.
  CHECK(run_argv(w, plot_args("mine.png")).status == 0);
  CHECK(asperity::png_is_ours(w / "mine.png"));
  CHECK(run_argv(w, plot_args("mine.png")).status == 0);
  CHECK(run_argv(w, plot_args("")).status == 0);
  CHECK(run_argv(w, plot_args("")).status == 0);
  CHECK(asperity::png_is_ours(w / "results" / "camp" / "heatmap_Q_s_over_model_eta_model_epsilon.png"));
  // The tag keeps the PNG valid: libpng (through gnuplot) reads it without a CRC complaint, and
  // does complain once one byte of the tag is changed.
  auto libpng_says = [&](const fs::path& png) {
    const fs::path err = w / "libpng.txt";
    const std::string cmd = "cd '" + w.string() + "' && printf \"set terminal dumb\\nset output '/dev/null'\\nplot '" +
                            png.filename().string() + "' binary filetype=png with rgbimage\\n\" | gnuplot 2>'" +
                            err.string() + "'";
    CHECK(std::system(cmd.c_str()) == 0);
    return slurp(err);
  };
  CHECK(libpng_says(w / "mine.png").find("CRC") == std::string::npos);
  {
    std::string bytes = slurp(w / "mine.png");
    const std::size_t at = bytes.find("asperity");
    REQUIRE(at != std::string::npos);
    bytes[at] = 'A';
    write_text(w / "bad.png", bytes);
  }
  CHECK(libpng_says(w / "bad.png").find("CRC error") != std::string::npos);
  CHECK_FALSE(asperity::png_is_ours(w / "bad.png"));
  fs::remove_all(w);
}

TEST_CASE("experiments named \"x y\" and \"x_y\" get separate fit outputs", "[cli][overwrite][fit]") {
  const fs::path w = make_case("xy");
  const CliResult r = run_argv(w, {"fit", "fit.yaml", "--out", "f", "--quiet", "--no-profile", "--no-error-bars"});
  INFO(r.err);
  REQUIRE(r.status != 2);
  const YAML::Node y = YAML::LoadFile((w / "f" / "fit.yaml").string());
  REQUIRE(y["fits"].size() == 2);
  std::set<std::string> folders;
  for (const auto& f : y["fits"]) {
    const std::string dir = f["files"].as<std::string>();
    folders.insert(dir);
    CHECK(fs::exists(w / "f" / dir / "evaluations.csv"));
    // Its own A(Q) files, named after its own experiment.
    std::size_t model_files = 0;
    for (const auto& e : fs::directory_iterator(w / "f" / dir))
      model_files += e.path().filename().string().size() > 10 && e.path().filename().string().ends_with("_model.csv");
    CHECK(model_files == 1);
  }
  CHECK(folders.size() == 2);
  CHECK(folders.count("x_y") == 1);  // the plain name keeps its own name
  fs::remove_all(w);
}

TEST_CASE("generate and bench write only into folders they created", "[cli][overwrite]") {
  const fs::path w = make_case("gen");
  const fs::path src(ASPERITY_SOURCE_DIR);
  const std::string recipe = (src / "bench" / "recipe.yaml").string();
  write_text(w / "notes" / "README.md", "# my notes\n");
  const std::string refused = "refusing to write there: it is not empty and was not written by asperity ";
  check_refused(w, {"generate", "--recipe", recipe, "--out", "notes", "--quiet"},
                "notes: --out: " + refused + "generate");
  check_refused(w, {"generate", "--recipe", recipe, "--out", "g", "--scenes", "user", "--quiet"},
                "user: --scenes: " + refused + "generate");
  check_refused(w, {"bench", "savings", "--out", "user", "--quick"}, "user: --out: " + refused + "bench");
  // Its own folders are written again.
  for (int k = 0; k < 2; ++k)
    CHECK(run_argv(w, {"generate", "--recipe", recipe, "--out", "g", "--scenes", "gs", "--quiet"}).status == 0);
  CHECK(slurp(w / "g" / ".asperity").rfind("created by asperity generate\nfiles v2\n", 0) == 0);
  CHECK(slurp(w / "gs" / ".asperity").rfind("created by asperity generate\nfiles v2\n", 0) == 0);
  // The committed stand-ins and bench inputs carry their file lists: written again in a copy; a
  // copy without its marker (it might hold edits) is refused.
  const fs::path old = w / "old";
  fs::create_directories(old);
  fs::copy(src / "bench" / "data", old / "data", fs::copy_options::recursive);
  fs::copy(src / "bench" / "scenes", old / "scenes", fs::copy_options::recursive);
  CHECK(
      run_argv(w, {"generate", "--recipe", recipe, "--out", "old/data", "--scenes", "old/scenes", "--quiet"}).status ==
      0);
  fs::remove(old / "data" / ".asperity");
  check_refused(w, {"generate", "--recipe", recipe, "--out", "old/data", "--quiet"},
                "old/data: --out: " + refused + "generate");
  fs::remove_all(w);
}

TEST_CASE("a rerun of generate refuses to replace an output the user edited, and keeps the edit", "[cli][overwrite]") {
  const fs::path w = make_case("gen-edit");
  const std::string recipe = (fs::path(ASPERITY_SOURCE_DIR) / "bench" / "recipe.yaml").string();
  const std::vector<std::string> gen = {"generate", "--recipe", recipe, "--out", "G", "--scenes", "S", "--quiet"};
  REQUIRE(run_argv(w, gen).status == 0);
  write_text(w / "G" / "notes.txt", "mine\n");
  REQUIRE(run_argv(w, gen).status == 0);  // a file the user added stays
  CHECK(slurp(w / "G" / "notes.txt") == "mine\n");
  for (const fs::path& edited : {w / "G" / "P0.20N" / "experiment.yaml", w / "S" / "P0.20N.yaml"}) {
    const std::string original = slurp(edited);
    write_text(edited, original + "# k_L edited by hand\n");
    const std::string option = edited.parent_path().filename() == "S" ? "--scenes" : "--out";
    check_refused(w, gen, edited.string() + ": " + option + ": refusing to replace it");  // nothing changed
    write_text(edited, original);
  }
  // Scenes written into the experiments' own folder: one write, which a rerun repeats.
  for (int k = 0; k < 2; ++k)
    CHECK(run_argv(w, {"generate", "--recipe", recipe, "--out", "B", "--scenes", "B", "--quiet"}).status == 0);
  CHECK(slurp(w / "B" / "P0.20N.yaml").find("experiment: P0.20N/experiment.yaml") != std::string::npos);
  // A synthetic experiment's folder likewise.
  asperity::testing::write_base_scene(w, 0.1, 10);
  write_text(w / "syn.yaml", asperity::testing::synthetic_recipe_text("base/scene.yaml", {}, 0.002, 7, 1.0));
  const std::vector<std::string> syn = {"generate", "--recipe", "syn.yaml", "--out", "Y", "--quiet"};
  REQUIRE(run_argv(w, syn).status == 0);
  REQUIRE(run_argv(w, syn).status == 0);
  write_text(w / "Y" / "experiment.yaml", slurp(w / "Y" / "experiment.yaml") + "# edited\n");
  check_refused(w, syn, (w / "Y" / "experiment.yaml").string() + ": --out: refusing to replace it");
  fs::remove_all(w);
}

TEST_CASE("links and FIFOs planted inside a store or fit folder are refused; nothing outside changes",
          "[cli][overwrite]") {
  const fs::path w = make_case("links");
  const std::vector<std::string> sweep = {"sweep", "camp.yaml", "--out", "s", "--quiet", "-j1"};
  const std::vector<std::string> fit = {"fit", "fit.yaml", "--out", "f", "--quiet", "--no-profile", "--no-error-bars"};
  REQUIRE(run_argv(w, sweep).status == 0);
  REQUIRE(run_argv(w, fit).status != 2);
  write_text(w / "outside" / "victim.csv", "not asperity's\n");
  fs::create_directories(w / "outside" / "dir");
  const auto outside = snapshot(w / "outside");
  const auto refused = [&](const std::vector<std::string>& args, const fs::path& planted) {
    const CliResult r = run_argv(w, args);
    INFO(args.front() << " with " << planted << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.err.find(planted.filename().string()) != std::string::npos);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(snapshot(w / "outside") == outside);
  };
  // points.csv, which a sweep only ever replaces (rename): the link itself is replaced by the
  // rebuilt file, never written through.
  fs::remove(w / "s" / "points.csv");
  fs::create_symlink(w / "outside" / "victim.csv", w / "s" / "points.csv");
  CHECK(run_argv(w, sweep).status == 0);
  CHECK(fs::is_regular_file(fs::symlink_status(w / "s" / "points.csv")));
  CHECK(snapshot(w / "outside") == outside);
  // journal.csv (store, fit) and the lock replaced by links to a file outside: refused.
  for (const fs::path& f : {w / "s" / "journal.csv", w / "s" / ".lock", w / "f" / "journal.csv", w / "f" / ".lock"}) {
    const fs::path keep = w / ("keep-" + f.parent_path().filename().string() + f.filename().string());
    fs::rename(f, keep);
    fs::create_symlink(w / "outside" / "victim.csv", f);
    refused(f.parent_path().filename() == "s" ? sweep : fit, f);
    fs::remove(f);
    fs::rename(keep, f);
  }
  // A FIFO as the journal: refused at once (it used to block the sweep forever).
  fs::rename(w / "s" / "journal.csv", w / "journal.keep");
  REQUIRE(::mkfifo((w / "s" / "journal.csv").c_str(), 0644) == 0);
  const auto t0 = std::chrono::steady_clock::now();
  refused(sweep, w / "s" / "journal.csv");
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(10));
  fs::remove(w / "s" / "journal.csv");
  fs::rename(w / "journal.keep", w / "s" / "journal.csv");
  // An array task's folder reached through a link (tasks -> outside/dir).
  fs::create_directory_symlink(w / "outside" / "dir", w / "f" / "tasks");
  std::vector<std::string> task = fit;
  task.insert(task.end(), {"--task", "0/2"});
  refused(task, w / "f" / "tasks");
  fs::remove(w / "f" / "tasks");
  // A foreign header in the store's journal is bad input too (exit 2, naming line 1).
  const std::string journal = slurp(w / "s" / "journal.csv");
  write_text(w / "s" / "journal.csv", "index,something,else,sha256\n");
  const CliResult r = run_argv(w, sweep);
  CHECK(r.status == 2);
  CHECK(r.err.find("journal.csv:1: header:") != std::string::npos);
  write_text(w / "s" / "journal.csv", journal);
  // With everything put back, both resume to what they had.
  CHECK(run_argv(w, sweep).status == 0);
  CHECK(run_argv(w, fit).status != 2);
  CHECK(snapshot(w / "outside") == outside);
  fs::remove_all(w);
}

TEST_CASE("a folder a stopped or failed merge left is merged into again; an export's stale temporary goes",
          "[cli][overwrite][campaign]") {
  const fs::path w = make_case("merge_rerun");
  REQUIRE(run_argv(w, {"sweep", "camp.yaml", "--quiet", "-j", "1"}).status == 0);
  const std::string points = slurp(w / "results" / "camp" / "points.csv");
  // A temporary a dead process left (a day old: stale whatever its host).
  const auto stale = [&](const fs::path& p) {
    write_text(p, "half written\n");
    fs::last_write_time(p, fs::file_time_type::clock::now() - std::chrono::hours(48));
  };
  // Stopped by a signal: its lock and a temporary (kill -9 leaves one; SIGTERM removes its own).
  fs::create_directories(w / "m_stopped");
  write_text(w / "m_stopped" / ".lock", "");
  stale(w / "m_stopped" / ".journal.csv.tmp-host-1-0");
  // Failed on a full disk while writing the journal, the last file: all but journal.csv.
  REQUIRE(run_argv(w, {"merge", "results/camp", "--out", "m_full", "--quiet"}).status == 0);
  fs::remove(w / "m_full" / "journal.csv");
  stale(w / "m_full" / ".journal.csv.tmp-host-1-0");
  for (const char* out : {"m_stopped", "m_full"}) {
    INFO(out);
    const CliResult r = run_argv(w, {"merge", "results/camp", "--out", out, "--quiet"});
    INFO(r.err);
    CHECK(r.status == 0);
    CHECK(slurp(w / out / "points.csv") == points);
    CHECK(fs::exists(w / out / "journal.csv"));
    CHECK_FALSE(fs::exists(w / out / ".journal.csv.tmp-host-1-0"));
    // Done: merge never adds to a store.
    CHECK(run_argv(w, {"merge", "results/camp", "--out", out, "--quiet"}).status == 2);
  }
  // Still refused: a user's file beside a lock, or a provenance.yaml that is not a store's.
  fs::create_directories(w / "m_user");
  write_text(w / "m_user" / ".lock", "");
  write_text(w / "m_user" / "notes.txt", "mine\n");
  check_refused(w, {"merge", "results/camp", "--out", "m_user", "--quiet"},
                "m_user: --out: refusing to write there: it is not empty and was not written by asperity merge");
  write_text(w / "m_prov" / "provenance.yaml", "# my own provenance\n");
  write_text(w / "m_prov" / "campaign.yaml", "name: mine\n");
  check_refused(w, {"merge", "results/camp", "--out", "m_prov", "--quiet"},
                "m_prov: --out: refusing to write there: it is not empty and was not written by asperity merge");
  // export --sqlite: a stale temporary of the same name is removed when the file is written.
  stale(w / ".e.db.tmp-host-1-0");
  stale(w / ".other.db.tmp-host-1-0");
  CHECK(run_argv(w, {"export", "results/camp", "--sqlite", "e.db"}).status == 0);
  CHECK_FALSE(fs::exists(w / ".e.db.tmp-host-1-0"));
  CHECK(fs::exists(w / ".other.db.tmp-host-1-0"));  // another file's: not this export's to remove
  fs::remove_all(w);
}

TEST_CASE("outputs named with 250 or 255 bytes (legal names) are written by run, fit, sweep and export",
          "[cli][overwrite][names]") {
  const fs::path w = make_case("long_names");
  // The temporaries beside them add a prefix and a suffix; they must stay within NAME_MAX too.
  for (const std::size_t n : {250, 255}) {
    INFO(n << "-byte names");
    const std::string run_dir(n, 'r'), fit_dir(n, 'f'), store(n, 's'), db(n - 3, 'd');
    const CliResult run = run_argv(w, {"run", "s1.yaml", "--out", run_dir, "--quiet"});
    INFO(run.err);
    CHECK(run.status == 0);
    CHECK(fs::exists(w / run_dir / "summary.yaml"));
    const CliResult fit =
        run_argv(w, {"fit", "fit.yaml", "--out", fit_dir, "--quiet", "--no-profile", "--no-error-bars"});
    INFO(fit.err);
    CHECK(fit.status == 0);
    CHECK(fs::exists(w / fit_dir / "fit.yaml"));
    REQUIRE(run_argv(w, {"sweep", "camp.yaml", "--out", store, "--quiet", "-j", "1"}).status == 0);
    const CliResult exp = run_argv(w, {"export", store, "--sqlite", db + ".db"});
    INFO(exp.err);
    CHECK(exp.status == 0);
    CHECK_THAT(exp.out, Catch::Contains("exported 4 points"));
    CHECK(fs::file_size(w / (db + ".db")) > 0);
    // Nothing left behind but the outputs.
    for (const auto& e : fs::directory_iterator(w))
      CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
  }
  fs::remove_all(w);
}

TEST_CASE("study and regress write only what they created", "[cli][overwrite]") {
  const fs::path w = make_case("study");
  const fs::path src(ASPERITY_SOURCE_DIR);
  const std::string refused = "refusing to write there: it is not empty and was not written by asperity ";
  for (const std::string kind : {"recovery", "interactions", "continuum"})
    check_refused(w, {"study", (src / "studies" / (kind + ".yaml")).string(), "--out", "user", "--quiet"},
                  "user: --out: " + refused + "study " + kind);
  // regress --update writes its golden file only over a golden file: a user's file named as the
  // golden is read first, refused at its line, and left as it was.
  const auto before = snapshot(w);
  const CliResult r =
      run_argv(w, {"regress", "--update", "--reason", "test", "--suite",
                   (src / "scenes" / "regression" / "suite.yaml").string(), "--golden", "user/table.csv"});
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.err.rfind("user/table.csv", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(snapshot(w) == before);
  fs::remove_all(w);
}
