#include "campaign/shard_plan.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>
#include <unordered_map>

#include "campaign/campaign_scenes.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_cost.hpp"

namespace asperity {

std::string shard_balance_name(ShardBalance b) { return b == ShardBalance::index ? "index" : "cost-v1"; }

ShardBalance parse_shard_balance(const std::string& text) {
  if (text == "index") return ShardBalance::index;
  if (text == "cost" || text == "cost-v1") return ShardBalance::cost;
  throw std::invalid_argument("--balance " + text + ": expected index (round robin) or cost (by expected run time)");
}

ShardPlan ShardPlan::round_robin(Shard shard, std::uint64_t total, ShardBalance label) {
  ShardPlan p;
  p.shard_ = shard;
  p.total_ = total;
  p.size_ = shard.size(total);
  p.balance_ = label;
  return p;
}

ShardPlan ShardPlan::by_cost(Shard shard, std::uint64_t total, const std::function<double(std::uint64_t)>& cost) {
  ShardPlan p;
  p.shard_ = shard;
  p.total_ = total;
  p.balance_ = ShardBalance::cost;
  p.mine_.assign(total, false);
  p.expected_s_.assign(shard.count, 0.0);
  // Min-heap of (expected seconds, shard): the lexicographic order breaks ties by shard index.
  using Load = std::pair<double, std::uint64_t>;
  std::vector<Load> heap;
  heap.reserve(shard.count);
  for (std::uint64_t s = 0; s < shard.count; ++s) heap.emplace_back(0.0, s);
  const auto later = std::greater<Load>();
  std::make_heap(heap.begin(), heap.end(), later);
  for (std::uint64_t i = 0; i < total; ++i) {
    std::pop_heap(heap.begin(), heap.end(), later);
    Load& least = heap.back();
    const double c = cost(i);
    least.first += std::isfinite(c) && c > 0 ? c : 0.0;
    if (least.second == shard.index) {
      p.mine_[i] = true;
      ++p.size_;
    }
    std::push_heap(heap.begin(), heap.end(), later);
  }
  for (const Load& l : heap) p.expected_s_[l.second] = l.first;
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

namespace {

// Numeric keys that change a run's expected cost (non-numeric values always may).
bool sets_cost(const std::string& key) {
  return key == "stop.time" || key == "solver.Ct" || key == "experiment.mass" || key == "experiment.k_L";
}

}  // namespace

ShardPlan plan_shard(const Campaign& c, Shard shard, ShardBalance balance) {
  const std::uint64_t total = c.size();
  if (balance == ShardBalance::index || shard.count == 1) return ShardPlan::round_robin(shard, total, balance);
  if (total > kMaxCostBalancedPoints)
    throw std::invalid_argument("--balance cost: " + std::to_string(total) + " points, more than the " +
                                std::to_string(kMaxCostBalancedPoints) + " a cost plan covers; use --balance index");
  const CampaignScenes scenes(c);
  auto scene_cost = [&](const Point& p) {
    try {
      return expected_run_seconds(make_problem(scenes.scene(p)));
    } catch (const std::exception&) {  // an invalid point fails at once: the fixed per-run part
      return expected_run_seconds(Problem{});
    }
  };
  // Grids none of whose axes sets the cost cost the same at every point of one base scene:
  // one scene per (grid, base scene) block. When that is every grid and every block costs the
  // same, the plan is round robin, without a pass over the points.
  std::vector<bool> varies(c.grids.size(), false);
  std::vector<std::vector<double>> block(c.grids.size());
  std::uint64_t first = 0;
  bool uniform = true;
  for (std::size_t g = 0; g < c.grids.size(); ++g) {
    for (const Axis& a : c.grids[g].axes) {
      bool numbers = a.kind != Axis::Kind::list;
      if (!numbers) numbers = std::all_of(a.values.begin(), a.values.end(), [](const AxisValue& v) { return v.is_number; });
      varies[g] = varies[g] || !numbers || sets_cost(a.key);
    }
    const std::uint64_t per_scene = c.grids[g].size();
    for (std::size_t s = 0; s < c.scenes.size(); ++s, first += per_scene)
      block[g].push_back(per_scene == 0 || varies[g] ? 0.0 : scene_cost(point_at(c, first)));
    uniform = uniform && !varies[g];
  }
  if (uniform) {
    const double c0 = block.empty() || block[0].empty() ? 0.0 : block[0][0];
    for (const auto& b : block)
      uniform = uniform && std::all_of(b.begin(), b.end(), [&](double x) { return x == c0; });
  }
  if (uniform) return ShardPlan::round_robin(shard, total, ShardBalance::cost);
  // Otherwise expected seconds per distinct combination of the values that set the cost.
  // Bounded: a campaign varying stop.time over 10⁶ values rebuilds scenes instead of growing it.
  std::unordered_map<std::string, double> memo;
  const std::size_t kMemo = 4096;
  auto cost = [&](std::uint64_t index) {
    const Point p = point_at(c, index);
    if (!varies[p.grid]) return block[p.grid][p.scene];
    std::string key = std::to_string(p.grid) + "|" + std::to_string(p.scene);
    for (const PointValue& v : p.values)
      if (!v.value.is_number || sets_cost(v.axis->key)) key.append("|").append(v.axis->key).append("=").append(v.value.text);
    if (const auto it = memo.find(key); it != memo.end()) return it->second;
    const double s = scene_cost(p);
    if (memo.size() >= kMemo) memo.clear();
    memo.emplace(std::move(key), s);
    return s;
  };
  return ShardPlan::by_cost(shard, total, cost);
}

}  // namespace asperity
