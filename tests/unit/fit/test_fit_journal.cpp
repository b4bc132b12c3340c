// The fit journal (fit/fit_journal.hpp): exact round trip of the evaluated values, torn and
// damaged lines, replay through run_fit, and the split of a separate fit into array tasks.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "fit/fit.hpp"
#include "fit/fit_inputs.hpp"
#include "fit/fit_journal.hpp"
#include "fit/fit_load.hpp"
#include "fit/fit_tasks.hpp"
#include "io/csv.hpp"
#include "io/hash.hpp"
#include "io/input_error.hpp"
#include "io/journal_line.hpp"
#include "support_files.hpp"

using namespace asperity;
namespace fs = std::filesystem;
using asperity::testing::slurp;
using asperity::testing::write_text;

namespace {

fs::path fresh_dir(const std::string& tag) { return asperity::testing::fresh_dir("asperity-fitjournal-" + tag); }

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

const fs::path kFixture = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "fit" / "fit.yaml";

}  // namespace

TEST_CASE(
    "fit journal: values read back bit for bit; a torn or damaged tail is dropped, damage before good lines refused",
    "[fit][journal]") {
  const fs::path d = fresh_dir("lines");
  const fs::path file = d / "journal.csv";
  // Values whose shortest text is long or special: 0.1 + 0.2, the smallest subnormal, -0, a
  // value from exp/log as parameter_value makes them, and a failed evaluation (NaN objective).
  Evaluation a;
  a.index = 1;
  a.values = {0.1 + 0.2, std::numeric_limits<double>::denorm_min(), -0.0,
              std::exp(std::log(0.1e-15) + 0.37 * std::log(50.0))};
  a.objective = 1.0 / 3.0;
  a.residuals = {1.0 / 3.0};
  a.wall_s = 0.0123;
  Evaluation b = a;
  b.index = 2;
  b.values[0] = 0.3;  // 0.1 + 0.2 != 0.3: a different point
  b.objective = std::numeric_limits<double>::quiet_NaN();
  b.status = "m010: \"solver\" failed, at t = 0.5";
  {
    FitJournal j;
    j.open(file, true);
    j.append("fit", "m010", a);
    j.append("refit experiment.E -1", "m,010", b);
  }
  const auto good_size = fs::file_size(file);
  {
    FitJournal j;
    j.open(file, false);
    CHECK(j.size() == 2);
    const auto ra = j.find("fit", "m010", a.values);
    REQUIRE(ra);
    for (std::size_t i = 0; i < a.values.size(); ++i) CHECK(same_bits(ra->values[i], a.values[i]));
    CHECK(same_bits(ra->objective, a.objective));
    CHECK(ra->wall_s == a.wall_s);
    const auto rb = j.find("refit experiment.E -1", "m,010", b.values);
    REQUIRE(rb);
    CHECK(std::isnan(rb->objective));
    CHECK(rb->status == b.status);
    CHECK_FALSE(j.find("fit", "m010", b.values));      // the other point
    CHECK_FALSE(j.find("profile", "m010", a.values));  // another part
    std::vector<double> next = a.values;
    next[3] = std::nextafter(next[3], 1.0);  // one ulp away: not journaled
    CHECK_FALSE(j.find("fit", "m010", next));
  }
  // A torn last line (kill -9 inside the write) and a damaged tail line are dropped, and cut off
  // when the journal is opened for appending: exactly the good bytes remain.
  const std::string good = slurp(file);
  write_text(file, good + "fit,m010,3,0.5,0.1,0.1,ok,0.01,0123456789abcdef\nfit,m010,4,0.5,0.1");
  {
    FitJournal j;
    j.open(file, true);
    CHECK(j.dropped_lines() == 2);
    CHECK(j.size() == 2);
  }
  CHECK(fs::file_size(file) == good_size);
  // Damage followed by a good line: refused, naming the line and key, the file untouched.
  std::string damaged = good;
  damaged[damaged.find(",ok,")] = ';';
  write_text(file, damaged);
  {
    FitJournal j;
    CHECK_THROWS_WITH(j.open(file, true), Catch::StartsWith(file.string() + ":2: check: damaged line"));
  }
  CHECK(slurp(file) == damaged);
  // A line whose checksum is right but whose fields are not numbers (hand-made): named by key.
  write_text(file, good + io::journal_line("fit,m010,3,0.5;abc,0.1,0.1,ok,0.01"));
  {
    FitJournal j;
    CHECK_THROWS_WITH(j.open(file, false), Catch::StartsWith(file.string() + ":4: x: not a ';'-separated list"));
  }
  write_text(file, "index,hash\n");
  {
    FitJournal j;
    CHECK_THROWS_WITH(j.open(file, false),
                      Catch::StartsWith(file.string() + ":1: header: not an asperity fit journal"));
  }
  // A torn header (damaged from outside: a write of ours ends with its newline) counts as an empty
  // journal: opened for appending it gets a whole header, and what is appended then reads back.
  // (It used to be written and then cut away with the torn text, leaving rows without a header.)
  write_text(file, good.substr(0, good.find('\n') / 2));
  {
    FitJournal j;
    j.open(file, true);
    CHECK(j.size() == 0);
    j.append("fit", "m010", a);
  }
  CHECK(slurp(file).substr(0, good.find('\n') + 1) == good.substr(0, good.find('\n') + 1));
  {
    FitJournal j;
    j.open(file, false);
    CHECK(j.size() == 1);
    REQUIRE(j.find("fit", "m010", a.values));
  }
  fs::remove_all(d);
}

namespace {
// Experiment m010 only, no profile or error bars: about 17 evaluations, well under a second.
FitOptions m010_only() {
  FitOptions o;
  o.threads = 2;
  o.profile = false;
  o.error_bars = false;
  o.only = {0};
  return o;
}
}  // namespace

TEST_CASE(
    "run_fit through a journal: a rerun replays every evaluation and gives the same fit; replay_only refuses a gap",
    "[fit][journal]") {
  const FitSpec spec = load_fit(kFixture);
  const fs::path d = fresh_dir("replay");
  FitOptions o = m010_only();
  FitResult first, again;
  {
    FitJournal j;
    j.open(d / "journal.csv", true);
    o.journal = &j;
    first = run_fit(spec, o);
  }
  REQUIRE(first.fits.size() == 1);
  const Optimization& f = first.fits[0];
  CHECK(f.label == "m010");
  CHECK(first.replayed == 0);
  CHECK(first.computed == f.evaluations);
  CHECK(f.evaluations > 5);
  // The journal holds one line per evaluation (header aside).
  const std::string text = slurp(d / "journal.csv");
  CHECK(static_cast<int>(std::count(text.begin(), text.end(), '\n')) == f.evaluations + 1);
  {
    FitJournal j;
    j.open(d / "journal.csv", true);
    o.journal = &j;
    again = run_fit(spec, o);
  }
  const Optimization& g = again.fits[0];
  CHECK(again.computed == 0);
  CHECK(again.replayed == f.evaluations);
  CHECK(g.evaluations == f.evaluations);
  CHECK(g.stop_reason == f.stop_reason);
  CHECK(same_bits(g.best[0], f.best[0]));
  CHECK(same_bits(g.objective, f.objective));
  // The fit recovers the alpha_b the fixture's curve was generated at (0.7e-15) within 1 %.
  CHECK(std::abs(f.best[0] / 0.7e-15 - 1) < 0.01);
  // Collect mode over an empty journal: the first evaluation is missing.
  FitJournal empty;
  o.journal = &empty;
  o.replay_only = true;
  CHECK_THROWS_AS(run_fit(spec, o), NotJournaled);
  fs::remove_all(d);
}

TEST_CASE("array tasks of a separate fit: experiments dealt longest first to the least loaded task", "[fit][journal]") {
  // The fixture's experiments m010, m015, m025 have 34, 44, 54 junctions.
  const FitSpec spec = load_fit(kFixture);
  using V = std::vector<std::size_t>;
  CHECK(task_optimizations(spec, {0, 1}) == V{0, 1, 2});
  CHECK(task_optimizations(spec, {0, 2}) == V{2});     // 54
  CHECK(task_optimizations(spec, {1, 2}) == V{0, 1});  // 44 + 34
  CHECK(task_optimizations(spec, {0, 3}) == V{2});
  CHECK(task_optimizations(spec, {1, 3}) == V{1});
  CHECK(task_optimizations(spec, {2, 3}) == V{0});
  CHECK(task_optimizations(spec, {3, 4}).empty());  // more tasks than experiments
  FitSpec joint = spec;
  joint.separate = false;
  CHECK_THROWS_AS(task_optimizations(joint, {0, 2}), std::invalid_argument);
  // --task names its option in parse errors (the sweep's parser, shared).
  CHECK_THROWS_WITH(io::parse_shard("3/3", {}, "--task"), Catch::StartsWith("--task 3/3: expected I/N"));
}

TEST_CASE("fit inputs.txt: a resume with another build, task, --set or file content is refused naming the key",
          "[fit][journal]") {
  const FitSpec spec = load_fit(kFixture);
  const fs::path d = fresh_dir("inputs");
  const fs::path file = d / "inputs.txt";
  const std::string mine = fit_inputs_text(spec, {}, "asperity 0.1.0 commit aaaaaaaaaaaa Release GCC 12.2.0", {0, 1});
  write_text(file, mine);
  CHECK_NOTHROW(check_fit_inputs(file, mine));
  // Every input file is listed by content, relative to the fit file: 1 fit file + 3 × 4 files.
  CHECK(std::count(mine.begin(), mine.end(), '\n') == 1 + 2 + 13);
  CHECK(mine.find("\nfile " + io::hex16(io::fnv1a64(slurp(kFixture))) + " fit fit.yaml\n") != std::string::npos);
  CHECK(mine.find(" measured m025/measured.csv\n") != std::string::npos);
  CHECK_THROWS_WITH(
      check_fit_inputs(file,
                       fit_inputs_text(spec, {}, "asperity 0.1.0 commit bbbbbbbbbbbb Release GCC 12.2.0", {0, 1})),
      Catch::StartsWith(file.string() + ":2: build: the journal was computed by 'asperity 0.1.0 commit aaaaaaaaaaaa"));
  CHECK_THROWS_WITH(
      check_fit_inputs(file,
                       fit_inputs_text(spec, {}, "asperity 0.1.0 commit aaaaaaaaaaaa Release GCC 12.2.0", {1, 2})),
      Catch::StartsWith(file.string() + ":3: task: the journal is array task 0/1, this run is 1/2"));
  CHECK_THROWS_WITH(
      check_fit_inputs(file, fit_inputs_text(spec, {"model.eta=50"},
                                             "asperity 0.1.0 commit aaaaaaaaaaaa Release GCC 12.2.0", {0, 1})),
      Catch::Contains("set: the journal was computed with 0 --set override(s), this run has 1"));
  // A binary whose code cannot be named resumes nothing, even its own journal.
  const std::string anonymous = fit_inputs_text(spec, {}, "", {0, 1});
  write_text(file, anonymous);
  CHECK_THROWS_WITH(check_fit_inputs(file, anonymous),
                    Catch::StartsWith(file.string() + ":2: build: this binary's code cannot be identified"));
  fs::remove_all(d);
}

TEST_CASE(
    "fit journal: a best line forged with a valid digest is refused against its re-run; a legacy FNV journal is "
    "read and rewritten with SHA-256",
    "[fit][journal]") {
  const FitSpec spec = load_fit(kFixture);
  const fs::path d = fresh_dir("forged");
  FitOptions o = m010_only();
  FitResult first;
  {
    FitJournal j;
    j.open(d / "journal.csv", true);
    o.journal = &j;
    first = run_fit(spec, o);
  }
  const Optimization& f = first.fits[0];
  // The line of the best evaluation, its objective set to 0 and its digest recomputed: the
  // journal's own check passes, the re-run at the optimum does not.
  const std::string text = slurp(d / "journal.csv");
  std::vector<std::string> lines;
  for (std::size_t at = 0, nl; (nl = text.find('\n', at)) != std::string::npos; at = nl + 1)
    lines.push_back(text.substr(at, nl - at));
  const std::string best_x = journal_values(f.best);
  int best_line = 0;
  std::string forged = lines[0] + "\n";
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::vector<std::string> fld = io::csv_split(std::string(io::journal_row(lines[i])));
    if (fld[3] == best_x && best_line == 0) {
      best_line = static_cast<int>(i) + 1;
      fld[4] = "0";
      fld[5] = "0";
      std::string row = fld[0];
      for (std::size_t k = 1; k < fld.size(); ++k) row += "," + fld[k];
      forged += io::journal_line(row);
    } else {
      forged += lines[i] + "\n";
    }
  }
  REQUIRE(best_line > 1);
  write_text(d / "journal.csv", forged);
  {
    FitJournal j;
    j.open(d / "journal.csv", true);
    o.journal = &j;
    try {
      run_fit(spec, o);
      FAIL("a forged best evaluation was taken as computed");
    } catch (const io::InputError& e) {
      CHECK(e.file == (d / "journal.csv").string());
      CHECK(e.line == best_line);
      CHECK(e.key == "objective");
      CHECK(std::string(e.what()).find("re-run") != std::string::npos);
    }
  }
  // The same forgery with an FNV-1a checksum (the format before SHA-256) in a SHA-256 journal is
  // a damaged line: refused where good lines follow it, never taken as computed.
  std::string fnv_forged = lines[0] + "\n";
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::string row(io::journal_row(lines[i]));
    fnv_forged +=
        static_cast<int>(i) + 1 == best_line ? row + "," + io::hex16(io::fnv1a64(row)) + "\n" : lines[i] + "\n";
  }
  write_text(d / "journal.csv", fnv_forged);
  if (best_line < static_cast<int>(lines.size())) {
    FitJournal j;
    CHECK_THROWS_AS(j.open(d / "journal.csv", true), io::InputError);
  }
  // A whole journal from before SHA-256 (header "...,check", FNV-1a lines): replayed as it is, then
  // rewritten with SHA-256 lines holding the same rows.
  std::string legacy = lines[0].substr(0, lines[0].rfind(',')) + ",check\n";
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::string row(io::journal_row(lines[i]));
    legacy += row + "," + io::hex16(io::fnv1a64(row)) + "\n";
  }
  write_text(d / "journal.csv", legacy);
  {
    FitJournal j;
    j.open(d / "journal.csv", true);
    o.journal = &j;
    const FitResult again = run_fit(spec, o);
    CHECK(again.computed == 0);
    CHECK(again.replayed == f.evaluations);
    CHECK(same_bits(again.fits[0].objective, f.objective));
  }
  CHECK(slurp(d / "journal.csv") == text);  // the same lines, each with its SHA-256
  fs::remove_all(d);
}
