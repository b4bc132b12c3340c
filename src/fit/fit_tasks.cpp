#include "fit/fit_tasks.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "batch/shard_plan.hpp"
#include "solve/core/problem.hpp"
#include "solve/core/run_cost.hpp"

namespace asperity {

std::vector<std::size_t> task_optimizations(const FitSpec& spec, const io::Shard& task) {
  if (!spec.separate) throw std::invalid_argument("a joint fit is one optimization and cannot be split into tasks");
  const std::size_t n = spec.experiments.size();
  std::vector<double> cost(n);
  for (std::size_t e = 0; e < n; ++e)  // the sweep's cost model: N·t, or N³·t with interactions
    cost[e] = expected_run_seconds(make_problem(spec.experiments[e].scene.build()));
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  std::vector<std::size_t> mine;
  deal_by_cost(
      n, task.count, [&](std::uint64_t k) { return cost[order[k]]; },
      [&](std::uint64_t k, std::uint64_t t) {
        if (t == task.index) mine.push_back(order[k]);
      });
  std::sort(mine.begin(), mine.end());
  return mine;
}

}  // namespace asperity
