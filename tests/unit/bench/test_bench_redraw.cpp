// `asperity bench savings|tradeoff --redraw`: the CSV a bench wrote read back field by field (to
// its printed precision), the figure's script drawn again from it byte for byte, nothing else
// written, and a bad field refused at its line and column. Rows from short real runs of the
// bench experiment P0.20N (a stand-in) and the committed results/bench CSVs.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bench/savings.hpp"
#include "bench/tradeoff.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "support_figures.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

namespace {

const fs::path kSource = ASPERITY_SOURCE_DIR;
const fs::path kScene = kSource / "bench/scenes/P0.20N.yaml";

// Short runs (one repeat each, the stick-slip cycles of P0.20N end by 0.78 s).
const std::vector<SavingRow>& measured_savings() {
  static const std::vector<SavingRow> rows = [] {
    SavingsOptions o;
    o.scenes = {kScene};
    o.overrides = {"stop.time=2", "stop.cycles=5"};
    o.repeats = 1;
    o.scratch = fresh_dir("bench_redraw_scratch");
    return run_savings(o);
  }();
  return rows;
}

const TradeoffResult& measured_tradeoff() {
  static const TradeoffResult r = [] {
    TradeoffOptions o;
    o.scene = kScene;
    o.Ct = {10, 20};
    o.tolerances = {1e-4, 1e-6};
    o.repeats = 1;
    return run_tradeoff(o);
  }();
  return r;
}

// `back` is `x` printed to `digits` significant digits: within half a unit of the last one.
bool printed_as(double back, double x, int digits) {
  if (!std::isfinite(x)) return std::isnan(x) ? std::isnan(back) : back == x;
  return std::abs(back - x) <= 0.5 * std::pow(10.0, 1 - digits) * std::abs(x) * (1 + 1e-12);
}

// Every file under `dir` with its bytes.
std::map<std::string, std::string> files_of(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out[e.path().filename().string()] = slurp(e.path());
  return out;
}

// `text` with field `column` of line `line` (1-based) replaced by `field`.
std::string with_field(const std::string& text, int line, std::size_t column, const std::string& field) {
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    lines.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  std::vector<std::string> f = io::csv_split(lines[static_cast<std::size_t>(line - 1)]);
  f[column] = field;
  std::string joined;
  for (const std::string& s : f) joined += (joined.empty() ? "" : ",") + s;
  lines[static_cast<std::size_t>(line - 1)] = joined;
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

// The InputError `redraw` throws: its file, line, column and key.
template <class F>
io::InputError error_of(F redraw) {
  try {
    redraw();
  } catch (const io::InputError& e) {
    return e;
  }
  FAIL("no InputError");
  return io::InputError("", 0, "", "");
}

}  // namespace

TEST_CASE("bench savings: rows read back from savings.csv to its printed precision", "[bench][redraw]") {
  const std::vector<SavingRow>& rows = measured_savings();
  REQUIRE(rows.size() == 6);
  const fs::path w = fresh_dir("bench_redraw_savings_csv");
  write_text(w / "savings.csv", savings_csv(rows));
  const std::vector<SavingRow> back = read_savings_csv(w / "savings.csv");
  REQUIRE(back.size() == rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const SavingRow &a = rows[i], &b = back[i];
    INFO("row " << i << ": " << a.saving << ", " << a.variant);
    CHECK(b.experiment == a.experiment);
    CHECK(b.saving == a.saving);
    CHECK(b.variant == a.variant);
    CHECK(b.baseline == a.baseline);
    CHECK(printed_as(b.wall_s, a.wall_s, 4));
    CHECK(printed_as(b.cpu_s, a.cpu_s, 4));
    CHECK(printed_as(b.write_s, a.write_s, 4));
    CHECK(b.repeats == a.repeats);
    CHECK(printed_as(b.t_end, a.t_end, 6));
    CHECK(b.steps == a.steps);
    CHECK(b.force_evals == a.force_evals);
    CHECK(b.series_bytes == a.series_bytes);
    CHECK_FALSE(b.stand_in);  // not in the CSV: redraw_savings takes it from the scene
  }
  // Read back, written again: the same text (total_s = wall_s + write_s is recomputed).
  CHECK(savings_csv(back) == savings_csv(read_savings_csv(w / "savings.csv")));
  done_with(w);
}

TEST_CASE("bench tradeoff: rows read back from work_precision.csv to its printed precision", "[bench][redraw]") {
  const TradeoffResult& r = measured_tradeoff();
  REQUIRE(r.rows.size() == 2 + 2 + 2);
  const fs::path w = fresh_dir("bench_redraw_tradeoff_csv");
  write_text(w / "work_precision.csv", work_precision_csv(r.rows));
  const std::vector<WorkPrecisionRow> back = read_work_precision_csv(w / "work_precision.csv");
  REQUIRE(back.size() == r.rows.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    const WorkPrecisionRow &a = r.rows[i], &b = back[i];
    INFO("row " << i << ": " << a.method << " " << a.setting);
    CHECK(b.experiment == a.experiment);
    CHECK(b.method == a.method);
    CHECK(printed_as(b.setting, a.setting, 6));
    CHECK(printed_as(b.wall_s, a.wall_s, 4));
    CHECK(printed_as(b.cpu_s, a.cpu_s, 4));
    CHECK(b.repeats == a.repeats);
    CHECK(printed_as(b.t_end, a.t_end, 10));
    CHECK(b.steps == a.steps);
    for (std::size_t k = 0; k < n_robust; ++k) {
      INFO(robust_names()[k]);
      if (std::isnan(a.value[k]))
        CHECK(std::isnan(b.value[k]));
      else
        CHECK(b.value[k] == a.value[k]);  // exact: the shortest text that reads back
      CHECK(printed_as(b.error[k], a.error[k], 4));
    }
  }
  done_with(w);
}

TEST_CASE("bench: the committed results/bench CSVs read back and write again as they are", "[bench][redraw]") {
  const fs::path wp = kSource / "results/bench/work_precision.csv";
  CHECK(work_precision_csv(read_work_precision_csv(wp)) == slurp(wp));
  // savings.csv: every field but total_s, which was printed from the unrounded times.
  const fs::path sv = kSource / "results/bench/savings.csv";
  const io::TextTable was = io::read_text_table(sv, sv.string(), 100);
  const fs::path w = fresh_dir("bench_redraw_committed");
  const io::TextTable now =
      io::read_text_table(write_text(w / "savings.csv", savings_csv(read_savings_csv(sv))), "now", 100);
  REQUIRE(now.columns == was.columns);
  REQUIRE(now.rows.size() == was.rows.size());
  const std::size_t total = was.column("total_s");
  for (std::size_t i = 0; i < was.rows.size(); ++i)
    for (std::size_t c = 0; c < was.columns.size(); ++c) {
      INFO("line " << was.lines[i] << ", " << was.columns[c]);
      if (c == total)
        CHECK(std::abs(std::stod(now.rows[i][c]) / std::stod(was.rows[i][c]) - 1) < 1e-3);
      else
        CHECK(now.rows[i][c] == was.rows[i][c]);
    }
  done_with(w);
}

TEST_CASE("bench --redraw: the run's figure script again, byte for byte, and nothing else written", "[bench][redraw]") {
  const FigureFormats png;
  std::string why;
  {
    const fs::path w = fresh_dir("bench_redraw_savings");
    write_savings(w, measured_savings(), png);
    const std::map<std::string, std::string> run = files_of(w);
    REQUIRE(run.count("savings.gp"));
    CHECK(run.at("savings.gp").find(kStandInMark) != std::string::npos);  // P0.20N is a stand-in
    fs::remove(w / "savings.gp");
    fs::remove(w / "savings.png");
    CHECK(redraw_savings(w, {kScene}, png, &why) == io::gnuplot_available());
    INFO(why);
    const std::map<std::string, std::string> redrawn = files_of(w);
    CHECK(redrawn.at("savings.gp") == run.at("savings.gp"));
    CHECK(redrawn.at("savings.csv") == run.at("savings.csv"));
    for (const auto& [name, bytes] : redrawn) CHECK(run.count(name) == 1);  // nothing new
    if (io::gnuplot_available()) CHECK(png_is_ours(w / "savings.png"));
    done_with(w);
  }
  {
    const fs::path w = fresh_dir("bench_redraw_tradeoff");
    write_tradeoff(w, measured_tradeoff(), png);
    const std::map<std::string, std::string> run = files_of(w);
    REQUIRE(run.count("work_precision.gp"));
    CHECK(run.at("work_precision.gp").find(kStandInMark) != std::string::npos);
    fs::remove(w / "work_precision.gp");
    fs::remove(w / "work_precision.png");
    CHECK(redraw_tradeoff(w, kScene, png, &why) == io::gnuplot_available());
    INFO(why);
    const std::map<std::string, std::string> redrawn = files_of(w);
    CHECK(redrawn.at("work_precision.gp") == run.at("work_precision.gp"));
    for (const char* csv : {"work_precision.csv", "reference_order.csv"}) CHECK(redrawn.at(csv) == run.at(csv));
    for (const auto& [name, bytes] : redrawn) CHECK(run.count(name) == 1);
    done_with(w);
  }
}

TEST_CASE("bench --redraw refuses a bad CSV at its line and column and draws nothing", "[bench][redraw]") {
  const fs::path w = fresh_dir("bench_redraw_bad");
  const fs::path sv = w / "savings.csv", wp = w / "work_precision.csv";
  const std::string savings = savings_csv(measured_savings());
  const std::string precision = work_precision_csv(measured_tradeoff().rows);
  auto redraw_s = [&] { redraw_savings(w, {kScene}, FigureFormats{}); };
  auto redraw_t = [&] { redraw_tradeoff(w, kScene, FigureFormats{}); };

  SECTION("a number that is not one") {
    write_text(sv, with_field(savings, 3, 5, "0.12x"));  // cpu_s, the sixth column
    io::InputError e = error_of(redraw_s);
    CHECK(e.file == io::input_path(sv));
    CHECK(e.line == 3);
    CHECK(e.column == 6);
    CHECK(e.key == "cpu_s");
    CHECK_THAT(e.what(), Catch::Matchers::StartsWith(io::input_path(sv) + ":3:6: cpu_s: expected a number"));
    write_text(wp, with_field(precision, 4, 14, "abc"));  // relerr_Q_s
    e = error_of(redraw_t);
    CHECK(e.file == io::input_path(wp));
    CHECK(e.line == 4);
    CHECK(e.column == 15);
    CHECK(e.key == "relerr_Q_s");
  }
  SECTION("a count with a fraction, a baseline neither yes nor no") {
    write_text(sv, with_field(savings, 2, 10, "1.5"));  // steps
    CHECK(error_of(redraw_s).line == 2);
    write_text(sv, with_field(savings, 7, 3, "maybe"));  // baseline
    const io::InputError e = error_of(redraw_s);
    CHECK(e.line == 7);
    CHECK(e.key == "baseline");
  }
  SECTION("a missing column, a missing file, another experiment") {
    write_text(sv, "experiment,saving,variant\nP0.20N,series,x\n");
    CHECK(error_of(redraw_s).key == "baseline");
    CHECK(error_of(redraw_t).message.find("file not found") == 0);
    write_text(wp, with_field(precision, 5, 0, "P9.99N"));
    const io::InputError e = error_of(redraw_t);
    CHECK(e.line == 5);
    CHECK(e.key == "experiment");
  }
  CHECK_FALSE(fs::exists(w / "savings.png"));
  CHECK_FALSE(fs::exists(w / "savings.gp"));
  CHECK_FALSE(fs::exists(w / "work_precision.gp"));
  done_with(w);
}
