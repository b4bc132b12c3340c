// src/campaign/shard_plan.hpp: shards balanced by expected cost partition the points, reduce to
// round robin when costs are equal, keep the greedy bound max − min ≤ the costliest point, and
// deal a costly axis value evenly where round robin puts it on one shard; a sharded sweep under
// the cost plan merges to the unsharded store, and a store keeps the plan it was started with.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "campaign/campaign_load.hpp"
#include "campaign/campaign_scenes.hpp"
#include "campaign/merge.hpp"
#include "campaign/shard_plan.hpp"
#include "campaign/sweep.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_cost.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using asperity::testing::slurp;
using Catch::Matchers::Contains;

namespace {

std::vector<std::uint64_t> points_of(const ShardPlan& p, std::uint64_t total) {
  std::vector<std::uint64_t> out;
  for (std::uint64_t i = p.next(0); i < total; i = p.next(i + 1)) out.push_back(i);
  return out;
}

// points.csv without wall_s (the one value allowed to differ between runs).
std::vector<std::string> values_of(const fs::path& store) {
  std::vector<std::string> out;
  std::istringstream in(slurp(store / "points.csv"));
  for (std::string l; std::getline(in, l);) out.push_back(l.substr(0, l.rfind(',')));
  return out;
}

}  // namespace

TEST_CASE("a cost plan over equal costs is round robin, point for point", "[campaign][shard]") {
  for (std::uint64_t total : {0, 1, 7, 100, 101})
    for (std::uint64_t count : {1, 2, 3, 7})
      for (std::uint64_t s = 0; s < count; ++s) {
        const io::Shard shard{s, count};
        const ShardPlan cost = ShardPlan::by_cost(shard, total, [](std::uint64_t) { return 0.25; });
        const ShardPlan rr = ShardPlan::round_robin(shard, total);
        std::vector<std::uint64_t> modulo;
        for (std::uint64_t i = s; i < total; i += count) modulo.push_back(i);
        CHECK(points_of(cost, total) == modulo);
        CHECK(points_of(rr, total) == modulo);
        CHECK(cost.size() == modulo.size());
        CHECK(rr.size() == modulo.size());
      }
}

TEST_CASE("a cost plan partitions the points and keeps the greedy bound", "[campaign][shard]") {
  std::mt19937_64 rng(12345);
  std::lognormal_distribution<double> dist(0.0, 1.5);  // costs over ~two decades
  const std::uint64_t total = 2000, count = 7;
  std::vector<double> cost(total);
  for (double& c : cost) c = dist(rng);
  std::vector<int> owners(total, 0);
  std::vector<double> load(count, 0.0);
  std::vector<double> expected;
  for (std::uint64_t s = 0; s < count; ++s) {
    const ShardPlan p = ShardPlan::by_cost(io::Shard{s, count}, total, [&](std::uint64_t i) { return cost[i]; });
    for (std::uint64_t i = 0; i < total; ++i)
      if (p.contains(i)) ++owners[i], load[s] += cost[i];
    CHECK(points_of(p, total).size() == p.size());
    if (s == 0) expected = p.expected_s();
    CHECK(p.expected_s() == expected);  // every shard computes the same plan
  }
  CHECK(std::all_of(owners.begin(), owners.end(), [](int n) { return n == 1; }));
  for (std::uint64_t s = 0; s < count; ++s) CHECK(load[s] == Approx(expected[s]).epsilon(1e-12));
  const double spread = *std::max_element(load.begin(), load.end()) - *std::min_element(load.begin(), load.end());
  CHECK(spread <= *std::max_element(cost.begin(), cost.end()));

  // Costs alternating 100, 1 on two shards: round robin puts every costly point on shard 0
  // (spread 99 per pair); the cost plan stays within one costly point.
  std::vector<double> alt(1000);
  for (std::size_t i = 0; i < alt.size(); ++i) alt[i] = i % 2 == 0 ? 100.0 : 1.0;
  const ShardPlan p = ShardPlan::by_cost(io::Shard{0, 2}, alt.size(), [&](std::uint64_t i) { return alt[i]; });
  CHECK(std::abs(p.expected_s()[0] - p.expected_s()[1]) <= 100.0);
  const ShardPlan rr = ShardPlan::round_robin(io::Shard{0, 2}, alt.size());
  double rr0 = 0, rr1 = 0;
  for (std::size_t i = 0; i < alt.size(); ++i) (rr.contains(i) ? rr0 : rr1) += alt[i];
  CHECK(rr0 - rr1 == 99.0 * 500);
}

TEST_CASE("a sweep deals reference points over both shards, merges to the unsharded store, and keeps its plan",
          "[campaign][shard]") {
  const fs::path d = asperity::testing::fresh_dir("asperity_shard_plan");
  const fs::path scene = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "campaign" / "tiny_scene.yaml";
  {
    std::ofstream f(d / "methods.yaml");
    f << "name: methods\nscenes: [" << scene.string() << "]\nset: {stop.time: 0.05, solver.Ct: 4000}\n"
      << "axes:\n  model.eta: [0, 50, 100, 150]\n  solver.method: [reference, event]\n";
  }
  const Campaign c = load_campaign(d / "methods.yaml");
  REQUIRE(c.size() == 8);  // the last axis varies fastest: the even points run the reference scheme
  // The independent figure: each point's expected seconds from its own scene.
  const CampaignScenes scenes(c);
  std::vector<double> cost;
  for (std::uint64_t i = 0; i < c.size(); ++i)
    cost.push_back(expected_run_seconds(make_problem(scenes.scene(point_at(c, i)))));
  REQUIRE(cost[0] > 3 * cost[1]);  // reference ≫ event on these settings
  for (std::uint64_t s = 0; s < 2; ++s) {
    const ShardPlan rr = plan_shard(c, io::Shard{s, 2}, ShardBalance::index);
    const ShardPlan p = plan_shard(c, io::Shard{s, 2}, ShardBalance::cost);
    int reference = 0, reference_rr = 0;
    double load = 0;
    for (std::uint64_t i = 0; i < c.size(); ++i) {
      reference += p.contains(i) && i % 2 == 0;
      reference_rr += rr.contains(i) && i % 2 == 0;
      if (p.contains(i)) load += cost[i];
    }
    CHECK(reference == 2);                    // of the 4
    CHECK(reference_rr == (s == 0 ? 4 : 0));  // round robin: all on shard 0
    CHECK(p.expected_s()[s] == Approx(load).epsilon(1e-12));
  }

  auto sweep = [&](const fs::path& out, io::Shard shard, std::optional<ShardBalance> balance) {
    SweepOptions o;
    o.out = out;
    o.threads = 1;
    o.shard = shard;
    o.balance = balance;
    o.quiet = true;
    return run_sweep(c, o);
  };
  sweep(d / "whole", {}, std::nullopt);
  const SweepReport s0 = sweep(d / "s0", io::Shard{0, 2}, std::nullopt);
  const SweepReport s1 = sweep(d / "s1", io::Shard{1, 2}, std::nullopt);
  CHECK(s0.balance == ShardBalance::cost);
  CHECK(s0.ran == s0.points);
  CHECK(s0.ran + s1.ran == c.size());
  CHECK(s0.expected_s == Approx(s0.expected_max_s + s0.expected_min_s - s1.expected_s).epsilon(1e-12));
  CHECK(std::abs(s0.expected_s - s1.expected_s) <= *std::max_element(cost.begin(), cost.end()));
  CHECK_THAT(slurp(d / "s0" / "provenance.yaml"), Contains("shard_balance: \"cost-v1\""));
  merge_stores({d / "s1", d / "s0"}, d / "merged");
  CHECK(values_of(d / "merged") == values_of(d / "whole"));
  CHECK_THAT(slurp(d / "merged" / "provenance.yaml"), !Contains("shard_balance"));

  // A resumed store keeps its plan; asking another is refused (it would orphan stored points).
  CHECK(sweep(d / "s0", io::Shard{0, 2}, std::nullopt).ran == 0);
  CHECK_THROWS_WITH(sweep(d / "s0", io::Shard{0, 2}, ShardBalance::index), Contains("must use the same --balance"));
  // A store from before the plan was recorded dealt round robin, and resumes so.
  const SweepReport old = sweep(d / "old", io::Shard{1, 2}, ShardBalance::index);
  CHECK(old.ran == 4);
  std::string prov = slurp(d / "old" / "provenance.yaml");
  prov.erase(prov.find("shard_balance:"),
             prov.find('\n', prov.find("shard_balance:")) + 1 - prov.find("shard_balance:"));
  std::ofstream(d / "old" / "provenance.yaml", std::ios::binary) << prov;
  const SweepReport again = sweep(d / "old", io::Shard{1, 2}, std::nullopt);
  CHECK(again.balance == ShardBalance::index);
  CHECK(again.ran == 0);
  fs::remove_all(d);
}
