// asperity export STORE --sqlite FILE: the store's rows in a typed SQLite table; an aggregate in
// SQL equals the same aggregate computed here from points.csv; an existing FILE is never replaced.
#include <sqlite3.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "campaign/campaign_load.hpp"
#include "campaign/export_sqlite.hpp"
#include "campaign/store.hpp"
#include "campaign/sweep.hpp"
#include "cli_spawn.hpp"
#include "io/numbers.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using Catch::Matchers::Contains;

namespace {

// Rows of a query, every value as text (NULL as "NULL", reals in their shortest exact spelling).
std::vector<std::vector<std::string>> query(const fs::path& db, const std::string& sql) {
  sqlite3* h = nullptr;
  REQUIRE(sqlite3_open_v2(db.c_str(), &h, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  INFO(sql);
  REQUIRE(sqlite3_prepare_v2(h, sql.c_str(), -1, &st, nullptr) == SQLITE_OK);
  std::vector<std::vector<std::string>> rows;
  while (sqlite3_step(st) == SQLITE_ROW) {
    std::vector<std::string> r;
    for (int c = 0; c < sqlite3_column_count(st); ++c) {
      const int type = sqlite3_column_type(st, c);
      if (type == SQLITE_NULL)
        r.push_back("NULL");
      else if (type == SQLITE_FLOAT)
        r.push_back(io::format_double(sqlite3_column_double(st, c)));  // exact
      else
        r.push_back(reinterpret_cast<const char*>(sqlite3_column_text(st, c)));
    }
    rows.push_back(r);
  }
  sqlite3_finalize(st);
  sqlite3_close(h);
  return rows;
}

double real_of(const std::string& s) { return std::stod(s); }

}  // namespace

TEST_CASE("export --sqlite: typed columns, SQL aggregates equal those of points.csv, never overwrites",
          "[campaign][export]") {
  const fs::path d = asperity::testing::temp_path("asperity_export");
  fs::remove_all(d);
  fs::create_directories(d);
  const Campaign c = load_campaign(fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "campaign" / "tiny.yaml");
  SweepOptions o;
  o.out = d / "store";
  o.threads = 1;
  o.quiet = true;
  REQUIRE(run_sweep(c, o).ok == c.size());

  const SqliteExportReport r = export_sqlite(d / "store", d / "tiny.sqlite");
  CHECK(r.rows == c.size());
  CHECK(r.indexes == c.varied_keys().size());  // model.eta, model.epsilon, experiment.mass, model.alpha_b

  // The truth, from points.csv: per grid, the number of rows, the mean of Q_s over the rows where
  // it is a number, the sum of steps, and the mean of t_end where model.eta = 100.
  const std::string text = asperity::testing::slurp(d / "store" / "points.csv");
  std::vector<std::vector<std::string>> rows;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t nl = text.find('\n', at);
    rows.push_back(io::csv_split(text.substr(at, nl - at)));
    at = nl + 1;
  }
  const std::vector<std::string> header = rows.front();
  auto col = [&](const std::string& n) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), n) - header.begin());
  };
  struct Group {
    int n = 0, q_n = 0;
    double q_sum = 0, steps = 0;
  };
  std::map<std::string, Group> truth;
  double t_end_sum = 0;
  int t_end_n = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const auto& f = rows[i];
    Group& g = truth[f[col("grid")]];
    ++g.n;
    g.steps += std::stod(f[col("steps")]);
    if (f[col("Q_s")] != "nan") ++g.q_n, g.q_sum += std::stod(f[col("Q_s")]);
    if (f[col("model.eta")] == "100") t_end_sum += std::stod(f[col("t_end")]), ++t_end_n;
  }
  REQUIRE(truth.size() == 2);
  REQUIRE(truth["eta_eps"].q_n > 0);

  // Measured: the SQL means equal these to the last bit (SQLite 3.40 sums in row order, as here);
  // the bound allows a few ulps for an SQLite that sums otherwise (compensated summation).
  const auto got =
      query(d / "tiny.sqlite",
            "SELECT grid, COUNT(*), AVG(Q_s), SUM(steps), COUNT(Q_s) FROM points GROUP BY grid ORDER BY grid");
  REQUIRE(got.size() == 2);
  for (const auto& g : got) {
    INFO("grid " << g[0]);
    const Group& t = truth.at(g[0]);
    CHECK(std::stoi(g[1]) == t.n);
    CHECK(std::stoi(g[4]) == t.q_n);  // nan is NULL, which AVG and COUNT skip
    if (t.q_n > 0) CHECK(real_of(g[2]) == Approx(t.q_sum / t.q_n).epsilon(1e-15));
    CHECK(std::stod(g[3]) == t.steps);  // an INTEGER sum: exact
  }
  // The index on a varied key serves an equality filter, and the quoted dotted name works.
  const auto eta = query(d / "tiny.sqlite", "SELECT COUNT(*), AVG(t_end) FROM points WHERE \"model.eta\" = 100");
  CHECK(std::stoi(eta[0][0]) == t_end_n);
  CHECK(real_of(eta[0][1]) == Approx(t_end_sum / t_end_n).epsilon(1e-15));
  const auto plan = query(d / "tiny.sqlite", "EXPLAIN QUERY PLAN SELECT * FROM points WHERE \"model.eta\" = 100");
  CHECK_THAT(plan.at(0).back(), Contains("USING INDEX points_by_1"));

  // Types: counts INTEGER, reals REAL, names TEXT, flags 0/1; a real that was nan is NULL.
  const auto types =
      query(d / "tiny.sqlite",
            "SELECT typeof(\"index\"), typeof(hash), typeof(\"model.eta\"), typeof(steps), typeof(t_end), "
            "typeof(peak_found), peak_found IN (0, 1), typeof(status) FROM points WHERE \"index\" = 0");
  CHECK(types.at(0) == std::vector<std::string>{"integer", "text", "real", "integer", "real", "integer", "1", "text"});
  CHECK(query(d / "tiny.sqlite", "SELECT COUNT(*) FROM store_files")[0][0] == "2");

  // An existing file is refused, in the library and on the command line (exit 2, one line),
  // and keeps its bytes.
  asperity::testing::write_text(d / "mine.sqlite", "not yours\n");
  CHECK_THROWS_WITH(export_sqlite(d / "store", d / "mine.sqlite"), Contains("exists"));
  const auto cli = asperity::testing::run_argv(d, {"export", "store", "--sqlite", "mine.sqlite"});
  CHECK(cli.status == 2);
  CHECK(cli.err == "mine.sqlite: --sqlite: exists; export writes a new file only (choose another name)\n");
  CHECK(asperity::testing::slurp(d / "mine.sqlite") == "not yours\n");
  // A file in a folder that does not exist: bad input (exit 2, one line), no folder made.
  const auto missing = asperity::testing::run_argv(d, {"export", "store", "--sqlite", "missing_dir/x.db"});
  CHECK(missing.status == 2);
  CHECK(missing.err ==
        "missing_dir/x.db: --sqlite: its folder missing_dir does not exist (export writes a file, it makes no "
        "folders)\n");
  CHECK_FALSE(fs::exists(d / "missing_dir"));
  // A store folder that is not a store: bad input.
  fs::create_directories(d / "not_a_store");
  asperity::testing::write_text(d / "not_a_store" / "points.csv", "a,b,c\n1,2,3\n");
  CHECK(asperity::testing::run_argv(d, {"export", "not_a_store", "--sqlite", "n.sqlite"}).status == 2);
  const auto fresh = asperity::testing::run_argv(d, {"export", "store", "--sqlite", "new.sqlite"});
  CHECK(fresh.status == 0);
  CHECK_THAT(fresh.out, Contains("exported 11 points"));
  // No temporary left beside it.
  for (const auto& e : fs::directory_iterator(d))
    CHECK(e.path().filename().string().find(".tmp-") == std::string::npos);
  fs::remove_all(d);
}
