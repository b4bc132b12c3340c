// src/campaign: the journal survives torn and corrupt lines; sweeps resume, are identical for 1
// and 2 threads and for merged shards, and record failing points.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "campaign/campaign_load.hpp"
#include "campaign/campaign_scenes.hpp"
#include "campaign/merge.hpp"
#include "campaign/store.hpp"
#include "campaign/sweep.hpp"
#include "io/csv.hpp"
#include "io/digest.hpp"
#include "io/hash.hpp"
#include "observe/series_csv.hpp"
#include "observe/simulate.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using Catch::Matchers::Contains;

namespace {

const fs::path& kData = asperity::testing::kCampaignData;

fs::path temp_dir() { return asperity::testing::numbered_dir("asperity_store"); }
using asperity::testing::slurp;

using asperity::testing::lines_of;

// points.csv without the wall_s column (the only value allowed to differ between runs).
std::vector<std::string> values_of(const fs::path& store) {
  std::vector<std::string> out;
  for (const std::string& l : lines_of(slurp(store / "points.csv"))) out.push_back(l.substr(0, l.rfind(',')));
  return out;
}

SweepReport sweep(const Campaign& c, const fs::path& out, int threads = 1, io::Shard shard = {}) {
  SweepOptions o;
  o.out = out;
  o.threads = threads;
  o.shard = shard;
  o.quiet = true;
  return run_sweep(c, o);
}

const std::string kHeader = "index,hash,grid,status,x";

}  // namespace

TEST_CASE("journal rows survive a reopen and a torn last line is dropped", "[campaign]") {
  const fs::path d = temp_dir();
  {
    Journal j(d, kHeader);
    CHECK(j.entries().empty());
    j.append("0,00000000000000aa,g,ok,1.5");
    j.append("1,00000000000000bb,g,failed,\"a, b\"");
    j.append("2,00000000000000cc,g,ok,3");
  }
  const std::string full = slurp(d / "journal.csv");
  // Tear the last line at every byte position: the first two rows always survive.
  const std::size_t third = full.find("2,00000000000000cc");
  for (std::size_t cut = third + 1; cut < full.size(); ++cut) {
    std::ofstream(d / "journal.csv", std::ios::binary | std::ios::trunc) << full.substr(0, cut);
    Journal j(d, kHeader);
    CHECK(j.dropped_lines() == 1);
    REQUIRE(j.entries().size() == 2);
    REQUIRE(j.find(0));
    CHECK(j.row(*j.find(0)) == "0,00000000000000aa,g,ok,1.5");
    CHECK(j.find(0)->ok());
    CHECK_FALSE(j.find(1)->ok());
    CHECK(j.row(*j.find(1)) == "1,00000000000000bb,g,failed,\"a, b\"");
    CHECK(slurp(d / "journal.csv") == full.substr(0, third));  // the torn bytes are gone
  }
  // Appending after recovery gives well-formed lines again.
  {
    Journal j(d, kHeader);
    j.append("2,00000000000000cc,g,ok,3");
  }
  CHECK(slurp(d / "journal.csv") == full);
}

TEST_CASE("journal lines with a bad checksum are dropped and the header is checked", "[campaign]") {
  const fs::path d = temp_dir();
  {
    Journal j(d, kHeader);
    j.append("0,00000000000000aa,g,ok,1.5");
    j.append("1,00000000000000bb,g,ok,2.5");
    j.append("2,00000000000000cc,g,ok,3.5");
  }
  std::string text = slurp(d / "journal.csv");
  text[text.find("2.5")] = '7';  // a flipped digit in the middle row
  std::ofstream(d / "journal.csv", std::ios::binary | std::ios::trunc) << text;
  {
    Journal j(d, kHeader);
    CHECK(j.dropped_lines() == 1);
    CHECK(j.entries().size() == 2);
    CHECK(j.find(1) == nullptr);
    REQUIRE(j.find(2));
    CHECK(j.row(*j.find(2)) == "2,00000000000000cc,g,ok,3.5");
  }
  CHECK_THROWS_WITH(Journal(d, "index,hash,grid,status,y"), Contains("another campaign"));
}

TEST_CASE("a sweep resumed after a torn or corrupt journal reruns only those points", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  const fs::path a = temp_dir() / "a";
  const SweepReport full = sweep(c, a, 2);
  CHECK(full.ran == c.size());
  CHECK(full.ok == c.size());
  const auto reference = values_of(a);
  REQUIRE(reference.size() == c.size() + 1);

  // Rerun: nothing to do.
  CHECK(sweep(c, a).ran == 0);
  // A folder holding other files is not taken for a store.
  const fs::path other = a.parent_path() / "other";
  fs::create_directories(other);
  std::ofstream(other / "points.csv") << "mine\n";
  std::ofstream(other / "notes.txt") << "mine\n";
  CHECK_THROWS_WITH(sweep(c, other), Contains("it holds 'notes.txt'"));
  CHECK(slurp(other / "points.csv") == "mine\n");

  // Tear the last journal line (as kill -9 in the middle of a write would), corrupt another.
  std::string j = slurp(a / "journal.csv");
  j.resize(j.size() - 7);
  const std::size_t row3 = j.find("\n3,") + 1;
  j[j.find(",ok,", row3) + 1] = 'O';
  std::ofstream(a / "journal.csv", std::ios::binary | std::ios::trunc) << j;
  fs::remove(a / "points.csv");
  const SweepReport resumed = sweep(c, a, 2);
  CHECK(resumed.dropped_lines == 2);
  CHECK(resumed.ran == 2);
  CHECK(resumed.skipped == c.size() - 2);
  CHECK(values_of(a) == reference);
  // Every journal line appears once per point: no duplicate rows in the final store.
  CHECK(lines_of(slurp(a / "journal.csv")).size() == c.size() + 1);
}

TEST_CASE("sweep values are identical for 1 and 2 threads and for merged shards", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  const fs::path d = temp_dir();
  sweep(c, d / "one", 1);
  sweep(c, d / "two", 2);
  const auto one = values_of(d / "one");
  CHECK(one.size() == c.size() + 1);
  CHECK(values_of(d / "two") == one);

  const SweepReport s0 = sweep(c, d / "s0", 2, io::Shard{0, 3});
  const SweepReport s1 = sweep(c, d / "s1", 1, io::Shard{1, 3});
  const SweepReport s2 = sweep(c, d / "s2", 2, io::Shard{2, 3});
  CHECK(s0.ran + s1.ran + s2.ran == c.size());
  CHECK(values_of(d / "s1").size() == 1 + 4);  // indices 1, 4, 7, 10
  const MergeReport m = merge_stores({d / "s2", d / "s0", d / "s1"}, d / "merged");
  // Another split (shard 4/5 builds point 9 right after point 4).
  std::vector<fs::path> fifths;
  for (std::uint64_t i = 0; i < 5; ++i) {
    fifths.push_back(d / ("f" + std::to_string(i)));
    sweep(c, fifths.back(), 1, io::Shard{i, 5});
  }
  merge_stores(fifths, d / "merged5");
  CHECK(values_of(d / "merged5") == one);
  CHECK(m.rows == c.size());
  CHECK(m.duplicates == 0);
  CHECK(values_of(d / "merged") == one);
  // The merged store is a store: resuming it has nothing left to do.
  CHECK(sweep(c, d / "merged").ran == 0);
  // Merging into an existing store is refused.
  CHECK_THROWS_WITH(merge_stores({d / "one", d / "merged"}, d / "merged"), Contains("already holds a store"));
}

TEST_CASE("a failing point is recorded with its error and counted and the campaign goes on", "[campaign]") {
  const fs::path d = temp_dir();
  // Ct = 2 makes the reference's explicit step unstable (SolverError) at every eta; Ct = 50 runs.
  std::ofstream(d / "fail.yaml") << "name: fail\nscenes: [" << (kData / "tiny_scene.yaml").string() << "]\n"
                                 << "set: {solver.method: reference, stop.time: 0.05}\n"
                                 << "axes: {solver.Ct: [2, 200]}\n";
  const Campaign c = load_campaign(d / "fail.yaml");
  const SweepReport r = sweep(c, d / "store", 2);
  CHECK(r.ran == 2);
  CHECK(r.failed == 1);
  CHECK(r.ok == 1);
  const auto rows = lines_of(slurp(d / "store" / "points.csv"));
  REQUIRE(rows.size() == 3);
  const auto header = io::csv_split(rows[0]);
  const auto failed = io::csv_split(rows[1]);
  const std::size_t status = Journal::status_column(rows[0]);
  CHECK(failed[status] == "failed");
  CHECK_THAT(failed[status + 1], Contains("unstable"));
  CHECK(io::csv_split(rows[2])[status] == "ok");

  // The command line counts it and exits 1.
  const std::string cmd = "'" + std::string(ASPERITY_BINARY) + "' sweep '" + (d / "fail.yaml").string() + "' --out '" +
                          (d / "cli").string() + "' --quiet 2>'" + (d / "err.txt").string() + "'";
  const int rc = std::system(cmd.c_str());
  CHECK(WEXITSTATUS(rc) == 1);
  CHECK_THAT(slurp(d / "err.txt"), Contains("1 ok, 1 failed"));
}

TEST_CASE("point hashes do not depend on where the project lives", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  const Scene s = CampaignScenes(c).scene(point_at(c, 0));
  FileHashes data;
  const std::string text = canonical_scene_text(s, kData, data);
  CHECK_THAT(text, Contains("file: \"../scene/exp_small/experiment.yaml\""));
  CHECK(text.find(ASPERITY_SOURCE_DIR) == std::string::npos);
}

TEST_CASE("a point's scene does not depend on the points built before it", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  std::vector<std::string> forward;
  FileHashes data;
  {
    const CampaignScenes scenes(c);
    for (std::uint64_t i = 0; i < c.size(); ++i)
      forward.push_back(canonical_scene_text(scenes.scene(point_at(c, i)), kData, data));
  }
  const CampaignScenes scenes(c);
  for (std::uint64_t i = c.size(); i-- > 0;) {
    INFO("point " << i);
    CHECK(canonical_scene_text(scenes.scene(point_at(c, i)), kData, data) == forward[i]);
    // Each point alone, on a fresh loader, too.
    CHECK(canonical_scene_text(CampaignScenes(c).scene(point_at(c, i)), kData, data) == forward[i]);
  }
  // The mass grid keeps the base scene's eta (100), whatever the grid before it set.
  CHECK(CampaignScenes(c).scene(point_at(c, 9)).model.eta == 100);
  CHECK(scenes.scene(point_at(c, 10)).model.eta == 100);
}

TEST_CASE("a per-point time limit fails the point and series are read back per point", "[campaign]") {
  const fs::path d = temp_dir();
  std::ofstream(d / "limit.yaml") << "name: limit\nscenes: [" << (kData / "tiny_scene.yaml").string() << "]\n"
                                  << "time_limit: 1e-9\naxes: {model.eta: [50, 100]}\n";
  const SweepReport r = sweep(load_campaign(d / "limit.yaml"), d / "limit", 2);
  CHECK(r.failed == 2);
  CHECK_THAT(slurp(d / "limit" / "points.csv"), Contains("per-point time limit of 1e-09 s exceeded"));

  std::ofstream(d / "series.yaml") << "name: series\nscenes: [" << (kData / "tiny_scene.yaml").string() << "]\n"
                                   << "series: true\naxes: {model.eta: [50, 100]}\n";
  const Campaign c = load_campaign(d / "series.yaml");
  CHECK(sweep(c, d / "series", 2).ok == 2);
  const auto texts = read_point_series(d / "series", {0, 1});
  REQUIRE(texts.size() == 2);
  for (const auto& [index, text] : texts) {
    const auto series = lines_of(text);
    CHECK(series.at(0) == "t,Q,A");  // the columns tiny_scene.yaml asks for
    CHECK(series.size() == 302);     // 0.3 s sampled every 1 ms: t = 0, 0.001, ..., 0.3
  }
}

namespace {

// Each point of `c` simulated alone, its series written as `asperity run` writes series.csv.
std::map<std::uint64_t, std::string> series_truth(const Campaign& c) {
  std::map<std::uint64_t, std::string> truth;
  const CampaignScenes scenes(c);
  for (std::uint64_t i = 0; i < c.size(); ++i) {
    const Scene sc = scenes.scene(point_at(c, i));
    std::ostringstream t;
    write_series_csv(t, simulate(sc).recorder.series(), sc.output.series);
    truth[i] = t.str();
  }
  return truth;
}

}  // namespace

TEST_CASE("series: one append-only file per store, read back per point, torn tail cut off, merged",
          "[campaign][series]") {
  const fs::path d = temp_dir();
  std::ofstream(d / "series.yaml") << "name: series\nscenes: [" << (kData / "tiny_scene.yaml").string() << "]\n"
                                   << "series: true\naxes: {model.eta: [50, 100, 150]}\n";
  const Campaign c = load_campaign(d / "series.yaml");
  const auto truth = series_truth(c);
  const fs::path s = d / "s";
  REQUIRE(sweep(c, s, 1).ok == 3);
  CHECK_FALSE(fs::exists(s / "series"));               // no file per point
  CHECK(read_point_series(s, {0, 1, 2, 7}) == truth);  // 7: no such point
  // One CSV: a header, every sample of every point, a trailer (a comment to pandas) per point.
  const std::string full = slurp(s / "series.csv");
  const std::string journal = slurp(s / "journal.csv");
  const auto lines = lines_of(full);
  CHECK(lines.front() == "index,t,Q,A");
  std::size_t samples = 0, trailers = 0;
  for (const auto& [i, t] : truth) samples += lines_of(t).size() - 1;
  for (const auto& l : lines) trailers += l.rfind("#end,", 0) == 0 ? 1 : 0;
  CHECK(trailers == 3);
  CHECK(lines.size() == 1 + samples + 3);

  // kill -9 while the last block was written: its journal row is not there yet (the block goes
  // first). At any cut, the resume cuts the torn block off and reruns that point only.
  const std::size_t last = full.rfind("#end,", full.rfind("#end,") - 1);
  const std::size_t start = full.find('\n', last) + 1;  // the last block's first byte
  const std::string journal_cut = journal.substr(0, journal.rfind('\n', journal.size() - 2) + 1);
  for (const std::size_t cut : {start + 1, start + (full.size() - start) / 3, full.size() - 30, full.size() - 1}) {
    INFO("series.csv cut at " << cut << " of " << full.size());
    std::ofstream(s / "series.csv", std::ios::binary | std::ios::trunc) << full.substr(0, cut);
    std::ofstream(s / "journal.csv", std::ios::binary | std::ios::trunc) << journal_cut;
    const SweepReport r = sweep(c, s, 1);
    CHECK(r.ran == 1);
    CHECK(slurp(s / "series.csv") == full);
  }
  // A power cut that kept a journal row but not its block: that point reruns.
  std::ofstream(s / "series.csv", std::ios::binary | std::ios::trunc) << full.substr(0, start);
  CHECK(sweep(c, s, 1).ran == 1);
  CHECK(slurp(s / "series.csv") == full);
  // A block superseded by a later one of another hash (as a rerun with changed data appends):
  // the point whose last block does not match its row reruns, and the end of the run leaves one
  // block per point.
  {
    SeriesFile f(s, true);
    f.append(0, 0x1234, "0,1,2,3\n");
  }
  CHECK(sweep(c, s, 1).ran == 1);
  CHECK(slurp(s / "series.csv") == full);

  // Merged shards hold every point's block.
  sweep(c, d / "a", 1, io::Shard{0, 2});
  sweep(c, d / "b", 1, io::Shard{1, 2});
  CHECK(read_point_series(d / "a", {0, 1, 2}).size() == 2);
  merge_stores({d / "b", d / "a"}, d / "m");
  CHECK(read_point_series(d / "m", {0, 1, 2}) == truth);
  CHECK(slurp(d / "m" / "series.csv") == full);  // blocks in index order, as the 1-thread run wrote them
}

TEST_CASE("a store with points.csv but no journal is plotted merged and resumed from points.csv", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  const fs::path d = temp_dir();
  sweep(c, d / "s", 2);
  const auto before = values_of(d / "s");
  fs::remove(d / "s" / "journal.csv");  // as in a clone: only points.csv is committed
  CHECK(StoreReader(d / "s").rows().size() == c.size());
  const SweepReport r = sweep(c, d / "s", 1);
  CHECK(r.ran == 0);
  CHECK(r.ok == c.size());
  CHECK(values_of(d / "s") == before);
  CHECK(lines_of(slurp(d / "s" / "journal.csv")).size() == c.size() + 1);
}

TEST_CASE("the typed scene used to recognise stored points hashes like the checked one", "[campaign]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");  // numeric axes only: every point has one
  const CampaignScenes scenes(c);
  FileHashes data;
  for (std::uint64_t i = 0; i < c.size(); ++i) {
    INFO("point " << i);
    const auto quick = scenes.unchecked_scene(point_at(c, i));
    REQUIRE(quick);
    CHECK(canonical_scene_text(*quick, kData, data) == canonical_scene_text(scenes.scene(point_at(c, i)), kData, data));
  }
  // A key that is not a plain number (here an enumeration) has none: the checked scene decides.
  const fs::path d = temp_dir();
  std::ofstream(d / "enum.yaml") << "name: enum\nscenes: [" << (kData / "tiny_scene.yaml").string() << "]\n"
                                 << "axes: {model.junction_shape: [elliptic, circular]}\n";
  const Campaign e = load_campaign(d / "enum.yaml");
  CHECK_FALSE(CampaignScenes(e).unchecked_scene(point_at(e, 0)));
}

TEST_CASE("store journal group commit: one fdatasync per group of points, every row kept", "[campaign][store]") {
  const fs::path d = temp_dir();
  {
    Journal j(d, kHeader, JournalSync{4, 0});
    for (int i = 0; i < 10; ++i) j.append(std::to_string(i) + ",00000000000000aa,g,ok," + std::to_string(i));
    CHECK(j.syncs() == 2);  // after rows 4 and 8; rows 9 and 10 wait for the next group
    j.sync();
    CHECK(j.syncs() == 3);
    j.sync();  // nothing appended since: no call
    CHECK(j.syncs() == 3);
  }
  {
    Journal j(d, kHeader, JournalSync{1, 0});
    CHECK(j.dropped_lines() == 0);
    REQUIRE(j.entries().size() == 10);
    REQUIRE(j.find(9));
    CHECK(j.row(*j.find(9)) == "9,00000000000000aa,g,ok,9");
    j.append("10,00000000000000aa,g,ok,10");
    CHECK(j.syncs() == 1);  // per point
  }

  // A sweep of 11 points synced every 7: after the 7th and at the end, 2 calls instead of 11,
  // and the same store as with one fdatasync per point.
  const Campaign c = load_campaign(kData / "tiny.yaml");
  SweepOptions o;
  o.quiet = true;
  o.threads = 2;
  o.out = d / "per_point";
  o.sync = {1, 0};
  const SweepReport per_point = run_sweep(c, o);
  CHECK(per_point.syncs == c.size());
  o.out = d / "grouped";
  o.sync = {7, 0};
  const SweepReport grouped = run_sweep(c, o);
  CHECK(grouped.ran == 11);
  CHECK(grouped.syncs == 2);
  CHECK(values_of(d / "grouped") == values_of(d / "per_point"));
  CHECK(run_sweep(c, o).syncs == 0);  // a resume with nothing to run appends nothing
}

TEST_CASE("the row index holds 16 bytes a row and keeps the last row written of each index", "[campaign][store]") {
  STATIC_REQUIRE(sizeof(StoredRow) == 16);
  RowIndex idx;
  // Indices out of order (the sweep journals out of order), index 5 written three times.
  const std::uint64_t rows[][3] = {{5, 0, 1}, {2, 10, 1}, {9, 20, 0}, {5, 30, 0}, {0, 40, 1}, {5, 50, 1}, {2, 60, 0}};
  for (const auto& r : rows) idx.add(r[0], r[1], r[2] == 1);
  CHECK(idx.rows().empty());  // nothing settled yet
  idx.settle();
  REQUIRE(idx.rows().size() == 4);
  std::vector<std::uint64_t> order;
  for (const StoredRow& r : idx.rows()) order.push_back(r.index);
  CHECK(order == std::vector<std::uint64_t>{0, 2, 5, 9});
  CHECK(idx.find(5)->offset() == 50);
  CHECK(idx.find(5)->ok());
  CHECK(idx.find(2)->offset() == 60);
  CHECK_FALSE(idx.find(2)->ok());
  CHECK(idx.find(3) == nullptr);
  // Added later: settled in with the rest, still the last written wins.
  idx.add(0, 70, false);
  idx.add(7, 80, true);
  idx.settle();
  REQUIRE(idx.rows().size() == 5);
  CHECK(idx.find(0)->offset() == 70);
  CHECK(idx.find(7)->ok());
}

TEST_CASE(
    "store journal: SHA-256 lines; a legacy FNV-1a journal is read and rewritten; an FNV line in a SHA-256 "
    "journal is damage",
    "[campaign][store]") {
  const fs::path d = temp_dir();
  {
    Journal j(d, kHeader);
    j.append("0,00000000000000aa,g,ok,1.5");
    j.append("1,00000000000000bb,g,ok,2.5");
  }
  const std::string sha_text = slurp(d / "journal.csv");
  const auto lines = lines_of(sha_text);
  REQUIRE(lines.size() == 3);
  CHECK(lines[0] == kHeader + ",sha256");
  // Independent: the line's digest is the FIPS SHA-256 of its row (as checked in test_io_digest).
  CHECK(lines[1] == "0,00000000000000aa,g,ok,1.5," + io::sha256_hex("0,00000000000000aa,g,ok,1.5"));
  // A legacy journal (header ",check", FNV-1a 64 per line), as written before SHA-256.
  const auto fnv_line = [](const std::string& row) { return row + "," + io::hex16(io::fnv1a64(row)) + "\n"; };
  std::ofstream(d / "journal.csv", std::ios::binary | std::ios::trunc)
      << kHeader + ",check\n" + fnv_line("0,00000000000000aa,g,ok,1.5") + fnv_line("1,00000000000000bb,g,ok,2.5");
  {
    Journal j(d, kHeader);
    CHECK(j.dropped_lines() == 0);
    CHECK(j.entries().size() == 2);
    REQUIRE(j.find(1));
    CHECK(j.row(*j.find(1)) == "1,00000000000000bb,g,ok,2.5");
  }
  CHECK(slurp(d / "journal.csv") == sha_text);  // migrated: the same rows with SHA-256
  // A row edited and given a fresh FNV-1a checksum (what a forger did before) is a bad line now.
  std::ofstream(d / "journal.csv", std::ios::binary | std::ios::app) << fnv_line("2,00000000000000cc,g,ok,0");
  {
    Journal j(d, kHeader);
    CHECK(j.dropped_lines() == 1);
    CHECK(j.find(2) == nullptr);
  }
}

TEST_CASE("a truncated or edited points.csv is rebuilt from the journal by the next run", "[campaign][store]") {
  const Campaign c = load_campaign(kData / "tiny.yaml");
  const fs::path a = temp_dir() / "a";
  SweepOptions o;
  o.out = a;
  o.threads = 2;
  o.quiet = true;
  o.build_id = "test-build";  // a known build: the next run trusts the stored hashes
  REQUIRE(run_sweep(c, o).ran == c.size());
  const std::string good = slurp(a / "points.csv");
  const SweepReport again = run_sweep(c, o);
  CHECK(again.trusted);
  CHECK(again.ran == 0);
  CHECK(slurp(a / "points.csv") == good);
  // Truncated (a disk full, a careless edit), then edited in place at the same size.
  std::ofstream(a / "points.csv", std::ios::binary | std::ios::trunc) << good.substr(0, good.size() / 2);
  CHECK(run_sweep(c, o).trusted);
  CHECK(slurp(a / "points.csv") == good);
  std::string edited = good;
  edited[edited.find(",ok,") + 1] = 'O';
  std::ofstream(a / "points.csv", std::ios::binary | std::ios::trunc) << edited;
  CHECK(run_sweep(c, o).ran == 0);
  CHECK(slurp(a / "points.csv") == good);
}
