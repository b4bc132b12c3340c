#pragma once
// Which points of a campaign one shard runs (`--shard I/N`, `--balance index|cost`): the plan of
// batch/shard_plan.hpp over the campaign's points, costed by their scenes.
// Why not round robin alone: an axis whose value sets the cost and whose length divides N (say
// model.interactions: [none, elastic] on 2 shards) puts every costly point on the same shard.
#include <cstdint>

#include "batch/shard_plan.hpp"
#include "campaign/campaign.hpp"

namespace asperity {

// More points than this are not cost-balanced (the plan is a pass over every point and a bit per
// point; its time: docs/performance.md): `cost` refuses, the default falls back to index.
inline constexpr std::uint64_t kMaxCostBalancedPoints = 100'000'000;

// The plan of `shard` of the campaign. cost: each point's expected_run_seconds, its scene built
// once per distinct combination of the values that set the cost (base scene, grid, experiment
// and other non-numeric values, stop.time, solver.Ct, experiment.mass, experiment.k_L); a point
// whose scene is invalid costs the fixed per-run part. Throws std::invalid_argument past
// kMaxCostBalancedPoints.
ShardPlan plan_shard(const Campaign& campaign, io::Shard shard, ShardBalance balance);

}  // namespace asperity
