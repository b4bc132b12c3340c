#pragma once
// Array tasks of a separate fit (`asperity fit FIT --task I/N`): which of its per-experiment
// optimizations task I of N runs. Experiments are dealt longest first to the task with the least
// estimated cost so far (batch/shard_plan.hpp's deal_by_cost; cost: the expected run time of
// solve/core/run_cost.hpp, the one the sweep's shards are balanced by: N·t, or N³·t with
// interactions; ties: lower experiment index, lower task), so the split depends only on the fit
// file and its data.
#include <cstddef>
#include <vector>

#include "fit/fit_spec.hpp"
#include "io/shard.hpp"

namespace asperity {

// Indices of the optimizations (= experiments, file order) of `task`, ascending. A joint fit is
// one optimization: std::invalid_argument.
std::vector<std::size_t> task_optimizations(const FitSpec& spec, const io::Shard& task);

}  // namespace asperity
