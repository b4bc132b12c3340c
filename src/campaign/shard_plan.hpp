#pragma once
// Which points of a campaign one shard runs (`--shard I/N`, `--balance index|cost`).
//
// index: round robin, the points with index % N == I.
// cost:  balanced by expected cost (solve/core/run_cost.hpp): the points, in index order, each go to
//        the shard with the least expected cost so far (ties: the lowest shard). Every shard
//        computes the same plan from the campaign alone (no coordination between array tasks).
//        Greedy list scheduling bounds the spread: the most loaded shard exceeds the least
//        loaded by at most the costliest single point. With equal costs it is round robin
//        exactly, so a campaign whose points all cost alike shards as it always did.
// Why not round robin alone: an axis whose value sets the cost and whose length divides N (say
// model.interactions: [none, elastic] on 2 shards) puts every costly point on the same shard.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "campaign/campaign.hpp"

namespace asperity {

enum class ShardBalance { index, cost };
// "index" or "cost-v1" (the version names the plan's rule and cost model: a store records it,
// and shards of one array must agree on it).
std::string shard_balance_name(ShardBalance b);
// "index", "cost" or "cost-v1"; std::invalid_argument otherwise.
ShardBalance parse_shard_balance(const std::string& text);

class ShardPlan {
 public:
  ShardPlan() = default;  // 0/1 of an empty campaign
  static ShardPlan round_robin(Shard shard, std::uint64_t total, ShardBalance label = ShardBalance::index);
  // `cost(i)` for i = 0 … total − 1 in order, each once; costs ≥ 0.
  static ShardPlan by_cost(Shard shard, std::uint64_t total, const std::function<double(std::uint64_t)>& cost);

  bool contains(std::uint64_t point) const;
  std::uint64_t size() const { return size_; }             // points of this shard
  std::uint64_t next(std::uint64_t from) const;           // its least point ≥ from, or total
  const Shard& shard() const { return shard_; }
  ShardBalance balance() const { return balance_; }
  // Expected seconds of every shard (by_cost only; empty otherwise).
  const std::vector<double>& expected_s() const { return expected_s_; }

 private:
  Shard shard_;
  std::uint64_t total_ = 0, size_ = 0;
  ShardBalance balance_ = ShardBalance::index;
  std::vector<bool> mine_;  // by_cost: one bit per point of the campaign (10⁷ points: 1.25 MB)
  std::vector<double> expected_s_;
};

// More points than this are not cost-balanced (the plan is a pass over every point, ~0.3 µs
// each when costs repeat, and a bit per point): `cost` refuses, the default falls back to index.
inline constexpr std::uint64_t kMaxCostBalancedPoints = 100'000'000;

// The plan of `shard` of the campaign. cost: each point's expected_run_seconds, its scene built
// once per distinct combination of the values that set the cost (base scene, grid, experiment
// and other non-numeric values, stop.time, solver.Ct, experiment.mass, experiment.k_L); a point
// whose scene is invalid costs the fixed per-run part. Throws std::invalid_argument past
// kMaxCostBalancedPoints.
ShardPlan plan_shard(const Campaign& campaign, Shard shard, ShardBalance balance);

}  // namespace asperity
