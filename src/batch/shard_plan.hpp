#pragma once
// Splitting a batch into N parts that run apart (a sweep's `--shard I/N`, a fit's `--task I/N`),
// with no coordination between them: every part computes the same plan from the inputs alone.
//
// index: round robin, the items with index % N == I.
// cost:  greedy list scheduling by expected cost (solve/core/run_cost.hpp): the items, in the
//        order given, each go to the part with the least expected cost so far (ties: the lowest
//        part). The most loaded part exceeds the least loaded by at most the costliest single
//        item. With equal costs, in index order, it is round robin exactly.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/shard.hpp"

namespace asperity {

// Deals `count` items to `parts` parts: for k = 0 … count − 1, item k (whatever the caller's order
// makes it) of cost `cost(k)` goes to the least loaded part, told by `take(k, part)`. Returns the
// expected cost of every part. Costs are taken as given (a caller clamps what it does not trust).
std::vector<double> deal_by_cost(std::uint64_t count, std::uint64_t parts,
                                 const std::function<double(std::uint64_t)>& cost,
                                 const std::function<void(std::uint64_t, std::uint64_t)>& take);

enum class ShardBalance { index, cost };
// "index" or "cost-v1" (the version names the plan's rule and cost model: a store records it,
// and shards of one array must agree on it).
std::string shard_balance_name(ShardBalance b);
// "index", "cost" or "cost-v1"; std::invalid_argument otherwise.
ShardBalance parse_shard_balance(const std::string& text);

// Which of `total` items (in index order) one shard runs.
class ShardPlan {
 public:
  ShardPlan() = default;  // 0/1 of an empty batch
  static ShardPlan round_robin(io::Shard shard, std::uint64_t total, ShardBalance label = ShardBalance::index);
  // `cost(i)` for i = 0 … total − 1 in order, each once; a cost that is not finite and > 0 counts 0.
  static ShardPlan by_cost(io::Shard shard, std::uint64_t total, const std::function<double(std::uint64_t)>& cost);

  bool contains(std::uint64_t point) const;
  std::uint64_t size() const { return size_; }   // points of this shard
  std::uint64_t next(std::uint64_t from) const;  // its least point ≥ from, or total
  const io::Shard& shard() const { return shard_; }
  ShardBalance balance() const { return balance_; }
  // Expected seconds of every shard (by_cost only; empty otherwise).
  const std::vector<double>& expected_s() const { return expected_s_; }

 private:
  io::Shard shard_;
  std::uint64_t total_ = 0, size_ = 0;
  ShardBalance balance_ = ShardBalance::index;
  std::vector<bool> mine_;  // by_cost: one bit per item (10⁷ items: 1.25 MB)
  std::vector<double> expected_s_;
};

}  // namespace asperity
