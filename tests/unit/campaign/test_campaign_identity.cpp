// src/campaign: a point's identity covers the bytes of its data. A junction area changed in place
// (same file name) makes a resume recompute the point and store the new value; merging a stale
// store with a fresh one is refused, naming the point and both hashes.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "campaign/campaign_load.hpp"
#include "campaign/merge.hpp"
#include "campaign/store.hpp"
#include "campaign/sweep.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using asperity::testing::slurp;
using Catch::Matchers::Contains;

namespace {

const fs::path kExperiment = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "scene" / "exp_small";

// A campaign of two points (eta 50, 100) on a private copy of the five-junction experiment.
fs::path make_campaign(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir / "exp");
  for (const char* f : {"experiment.yaml", "junctions.csv", "measured.csv"})
    fs::copy_file(kExperiment / f, dir / "exp" / f);
  std::ofstream(dir / "scene.yaml") << "experiment: exp/experiment.yaml\nsolver: {method: event}\n"
                                       "stop: {time: 0.05}\noutput: {series: []}\n";
  std::ofstream(dir / "campaign.yaml") << "name: identity\nscenes: [scene.yaml]\naxes: {model.eta: [50, 100]}\n";
  return dir / "campaign.yaml";
}

SweepReport sweep(const fs::path& campaign, const fs::path& out) {
  SweepOptions o;
  o.out = out;
  o.threads = 1;
  o.quiet = true;
  return run_sweep(load_campaign(campaign), o);
}

// Column `name` of every row of DIR/points.csv, by point index.
std::vector<std::string> column(const fs::path& store, const std::string& name) {
  const StoreReader s(store);
  const auto header = io::csv_split(s.header());
  const auto at = static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  REQUIRE(at < header.size());
  std::vector<std::string> out;
  for (const StoredRow& r : s.rows()) out.push_back(io::csv_split(s.row(r)).at(at));
  return out;
}

// Replaces the first `from` in a file by `to`, in place (same name, same folder).
void edit(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = slurp(file);
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

}  // namespace

TEST_CASE("a resume recomputes the points whose junction or measured CSV changed", "[campaign][identity]") {
  const fs::path dir = asperity::testing::temp_path("asperity_identity");
  const fs::path campaign = make_campaign(dir);
  const SweepReport first = sweep(campaign, dir / "store");
  CHECK(first.ran == 2);
  // A0 = Σ A0_i of the CSV: 1 + 2 + 1.5 + 3 + 0.5 (×1e-8 m²).
  for (const std::string& a0 : column(dir / "store", "A0")) CHECK(std::stod(a0) == Approx(8e-8).epsilon(1e-12));
  fs::copy(dir / "store", dir / "stale", fs::copy_options::recursive);

  // One area changes, the file keeps its name: both points are recomputed and store the new A0.
  edit(dir / "exp" / "junctions.csv", "0.0005,3e-8,", "0.0005,4e-8,");
  const SweepReport second = sweep(campaign, dir / "store");
  CHECK(second.skipped == 0);
  CHECK(second.changed == 2);
  CHECK(second.ran == 2);
  CHECK(second.ok == 2);
  for (const std::string& a0 : column(dir / "store", "A0")) CHECK(std::stod(a0) == Approx(9e-8).epsilon(1e-12));
  // points.csv holds one row per point (the stale rows superseded), and a rerun has nothing to do.
  CHECK(StoreReader(dir / "store").rows().size() == 2);
  const SweepReport third = sweep(campaign, dir / "store");
  CHECK(third.ran == 0);
  CHECK(third.changed == 0);

  // The measured curve is data too.
  edit(dir / "exp" / "measured.csv", "0.02,7.1e-8", "0.02,7.0e-8");
  CHECK(sweep(campaign, dir / "store").changed == 2);

  // The command line says so, even with --quiet.
  edit(dir / "exp" / "junctions.csv", "0,5e-9,", "0,6e-9,");
  const std::string cmd = "'" + std::string(ASPERITY_BINARY) + "' sweep '" + campaign.string() + "' --out '" +
                          (dir / "store").string() + "' --quiet -j1 2>'" + (dir / "err.txt").string() + "'";
  CHECK(std::system(cmd.c_str()) == 0);
  CHECK_THAT(slurp(dir / "err.txt"), Contains("2 stored point(s) recomputed: their scene or data"));
  for (const std::string& a0 : column(dir / "store", "A0")) CHECK(std::stod(a0) == Approx(9.1e-8).epsilon(1e-12));
  fs::remove_all(dir);
}

TEST_CASE("merge refuses stores whose rows disagree for one point", "[campaign][identity]") {
  const fs::path dir = asperity::testing::temp_path("asperity_identity_merge");
  const fs::path campaign = make_campaign(dir);
  sweep(campaign, dir / "stale");
  edit(dir / "exp" / "junctions.csv", "0.0005,3e-8,", "0.0005,4e-8,");
  sweep(campaign, dir / "fresh");
  const std::string stale_hash = column(dir / "stale", "hash").at(0), fresh_hash = column(dir / "fresh", "hash").at(0);
  CHECK(stale_hash != fresh_hash);
  // Stale + fresh: refused before anything is written, naming the point and both hashes.
  for (const auto& order :
       {std::vector<fs::path>{dir / "stale", dir / "fresh"}, std::vector<fs::path>{dir / "fresh", dir / "stale"}}) {
    CHECK_THROWS_WITH(merge_stores(order, dir / "merged"),
                      Contains("point 0 (grid grid_0, experiment small) was computed from different scenes or data") &&
                          Contains(stale_hash) && Contains(fresh_hash));
    CHECK_FALSE(fs::exists(dir / "merged"));
  }
  // The same point twice with the same hash and the same values merges (one row per point).
  fs::copy(dir / "fresh", dir / "fresh2", fs::copy_options::recursive);
  const MergeReport ok = merge_stores({dir / "fresh", dir / "fresh2"}, dir / "merged");
  CHECK(ok.rows == 2);
  CHECK(ok.duplicates == 2);
  // Same hash, different value (a store from another build, here forged): refused, naming the column.
  const std::string q = column(dir / "fresh2", "t_end").at(1);
  fs::remove(dir / "fresh2" / "journal.csv");  // the store is then read from points.csv
  edit(dir / "fresh2" / "points.csv", "," + q + ",", ",1" + q + ",");
  CHECK_THROWS_WITH(merge_stores({dir / "fresh", dir / "fresh2"}, dir / "merged2"),
                    Contains("(grid grid_0, experiment small), hash ") && Contains("t_end = " + q));
  CHECK_FALSE(fs::exists(dir / "merged2"));
  fs::remove_all(dir);
}

TEST_CASE("a resume trusts stored hashes while every input is unchanged and re-hashes them otherwise",
          "[campaign][identity][store]") {
  const fs::path dir = asperity::testing::temp_path("asperity_identity_trust");
  const fs::path campaign = make_campaign(dir);
  SweepOptions o;
  o.out = dir / "store";
  o.threads = 2;
  o.quiet = true;
  o.build_id = "test build 1";
  const auto run = [&](Campaign c) { return run_sweep(c, o); };
  const Campaign c = load_campaign(campaign);
  const SweepReport first = run(c);
  CHECK(first.ran == 2);
  CHECK_FALSE(first.trusted);
  // inputs.txt names every file the points' hashes depend on, with the FNV-1a 64 of its bytes.
  const std::string inputs = slurp(dir / "store" / "inputs.txt");
  for (const char* f : {"campaign.yaml", "scene.yaml", "exp/experiment.yaml", "exp/junctions.csv", "exp/measured.csv"})
    CHECK_THAT(inputs, Contains("file " + io::hex16(io::fnv1a64(slurp(dir / f))) + " " + f + "\n"));
  CHECK_THAT(inputs, Contains("build test build 1\nshard 0/1\n"));
  const std::string points = slurp(dir / "store" / "points.csv");

  // Unchanged: trusted, nothing rebuilt, re-hashed or run; points.csv the same bytes.
  SweepReport r = run(c);
  CHECK(r.trusted);
  CHECK(r.rehashed == 0);
  CHECK(r.skipped == 2);
  CHECK(r.ran == 0);
  CHECK(slurp(dir / "store" / "points.csv") == points);

  // Another build, or no inputs.txt (a killed run leaves none): every stored point is re-hashed
  // again, found current, and nothing runs.
  o.build_id = "test build 2";
  r = run(c);
  CHECK_FALSE(r.trusted);
  CHECK(r.rehashed == 2);
  CHECK(r.ran == 0);
  fs::remove(dir / "store" / "inputs.txt");
  r = run(c);
  CHECK_FALSE(r.trusted);
  CHECK(r.rehashed == 2);
  CHECK(r.ran == 0);
  CHECK(run(c).trusted);
  CHECK(slurp(dir / "store" / "points.csv") == points);

  // A --set entry (not in the campaign text) changes the points: not trusted, both recomputed.
  Campaign with_set = c;
  with_set.set.emplace_back("model.c_min", AxisValue{true, false, 0.02, "0.02"});
  r = run(with_set);
  CHECK_FALSE(r.trusted);
  CHECK(r.changed == 2);
  CHECK(r.ran == 2);
  r = run(c);  // and back
  CHECK_FALSE(r.trusted);
  CHECK(r.changed == 2);

  // A data file edited in place: not trusted, recomputed with the new area (Σ A0 = 9e-8 m²).
  CHECK(run(c).trusted);
  edit(dir / "exp" / "junctions.csv", "0.0005,3e-8,", "0.0005,4e-8,");
  r = run(c);
  CHECK_FALSE(r.trusted);
  CHECK(r.changed == 2);
  CHECK(r.ran == 2);
  for (const std::string& a0 : column(dir / "store", "A0")) CHECK(std::stod(a0) == Approx(9e-8).epsilon(1e-12));
  // No build id (a dirty or unknown build): never trusted, and no inputs.txt is written.
  o.build_id.clear();
  r = run(c);
  CHECK_FALSE(r.trusted);
  CHECK(r.rehashed == 2);
  CHECK_FALSE(fs::exists(dir / "store" / "inputs.txt"));
  fs::remove_all(dir);
}
