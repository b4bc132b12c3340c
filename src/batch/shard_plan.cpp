#include "batch/shard_plan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace asperity {

std::vector<double> deal_by_cost(std::uint64_t count, std::uint64_t parts,
                                 const std::function<double(std::uint64_t)>& cost,
                                 const std::function<void(std::uint64_t, std::uint64_t)>& take) {
  // Min-heap of (expected cost, part): the lexicographic order breaks ties by the lower part.
  using Load = std::pair<double, std::uint64_t>;
  std::vector<Load> heap;
  heap.reserve(parts);
  for (std::uint64_t s = 0; s < parts; ++s) heap.emplace_back(0.0, s);
  const auto later = std::greater<Load>();
  std::make_heap(heap.begin(), heap.end(), later);
  for (std::uint64_t k = 0; k < count; ++k) {
    std::pop_heap(heap.begin(), heap.end(), later);
    Load& least = heap.back();
    least.first += cost(k);
    take(k, least.second);
    std::push_heap(heap.begin(), heap.end(), later);
  }
  std::vector<double> load(parts, 0.0);
  for (const Load& l : heap) load[l.second] = l.first;
  return load;
}

std::string shard_balance_name(ShardBalance b) { return b == ShardBalance::index ? "index" : "cost-v1"; }

ShardBalance parse_shard_balance(const std::string& text) {
  if (text == "index") return ShardBalance::index;
  if (text == "cost" || text == "cost-v1") return ShardBalance::cost;
  throw std::invalid_argument("--balance " + text + ": expected index (round robin) or cost (by expected run time)");
}

ShardPlan ShardPlan::round_robin(io::Shard shard, std::uint64_t total, ShardBalance label) {
  ShardPlan p;
  p.shard_ = shard;
  p.total_ = total;
  p.size_ = shard.size(total);
  p.balance_ = label;
  return p;
}

ShardPlan ShardPlan::by_cost(io::Shard shard, std::uint64_t total, const std::function<double(std::uint64_t)>& cost) {
  ShardPlan p;
  p.shard_ = shard;
  p.total_ = total;
  p.balance_ = ShardBalance::cost;
  p.mine_.assign(total, false);
  p.expected_s_ = deal_by_cost(
      total, shard.count,
      [&](std::uint64_t i) {
        const double c = cost(i);
        return std::isfinite(c) && c > 0 ? c : 0.0;
      },
      [&](std::uint64_t i, std::uint64_t part) {
        if (part != shard.index) return;
        p.mine_[i] = true;
        ++p.size_;
      });
  return p;
}

bool ShardPlan::contains(std::uint64_t point) const {
  if (point >= total_) return false;
  return mine_.empty() ? shard_.contains(point) : mine_[point];
}

std::uint64_t ShardPlan::next(std::uint64_t from) const {
  if (from >= total_) return total_;
  if (mine_.empty()) {
    const std::uint64_t r = from % shard_.count;
    const std::uint64_t i = from - r + shard_.index + (r > shard_.index ? shard_.count : 0);
    return std::min(i, total_);
  }
  const auto it = std::find(mine_.begin() + static_cast<std::ptrdiff_t>(from), mine_.end(), true);
  return static_cast<std::uint64_t>(it - mine_.begin());
}

}  // namespace asperity
