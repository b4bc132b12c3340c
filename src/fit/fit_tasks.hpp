#pragma once
// Array tasks of a separate fit (`asperity fit FIT --task I/N`): which of its per-experiment
// optimizations task I of N runs. Experiments are dealt longest first to the task with the least
// estimated cost so far (cost: the experiment's junction count, what a run's time grows with;
// ties: lower experiment index, lower task), so the split depends only on the fit file.
#include <cstddef>
#include <vector>

#include "fit/fit_spec.hpp"
#include "io/shard.hpp"

namespace asperity {

// Indices of the optimizations (= experiments, file order) of `task`, ascending. A joint fit is
// one optimization: std::invalid_argument.
std::vector<std::size_t> task_optimizations(const FitSpec& spec, const Shard& task);

}  // namespace asperity
