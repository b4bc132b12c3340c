#include "campaign/shard_plan.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "campaign/campaign_scenes.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_cost.hpp"

namespace asperity {

namespace {

// Numeric keys that change a run's expected cost (non-numeric values always may).
bool sets_cost(const std::string& key) {
  return key == "stop.time" || key == "solver.Ct" || key == "experiment.mass" || key == "experiment.k_L";
}

}  // namespace

ShardPlan plan_shard(const Campaign& c, io::Shard shard, ShardBalance balance) {
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
      if (!numbers)
        numbers = std::all_of(a.values.begin(), a.values.end(), [](const AxisValue& v) { return v.is_number; });
      varies[g] = varies[g] || !numbers || sets_cost(a.key);
    }
    const std::uint64_t per_scene = c.grids[g].size();
    for (std::size_t s = 0; s < c.scenes.size(); ++s, first += per_scene)
      block[g].push_back(per_scene == 0 || varies[g] ? 0.0 : scene_cost(point_at(c, first)));
    uniform = uniform && !varies[g];
  }
  if (uniform) {
    const double c0 = block.empty() || block[0].empty() ? 0.0 : block[0][0];
    for (const auto& b : block) uniform = uniform && std::all_of(b.begin(), b.end(), [&](double x) { return x == c0; });
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
      if (!v.value.is_number || sets_cost(v.axis->key))
        key.append("|").append(v.axis->key).append("=").append(v.value.text);
    if (const auto it = memo.find(key); it != memo.end()) return it->second;
    const double s = scene_cost(p);
    if (memo.size() >= kMemo) memo.clear();
    memo.emplace(std::move(key), s);
    return s;
  };
  return ShardPlan::by_cost(shard, total, cost);
}

}  // namespace asperity
