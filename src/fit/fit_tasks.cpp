#include "fit/fit_tasks.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "solve/core/problem.hpp"
#include "solve/core/run_cost.hpp"

namespace asperity {

std::vector<std::size_t> task_optimizations(const FitSpec& spec, const Shard& task) {
  if (!spec.separate) throw std::invalid_argument("a joint fit is one optimization and cannot be split into tasks");
  const std::size_t n = spec.experiments.size();
  std::vector<double> cost(n);
  for (std::size_t e = 0; e < n; ++e)  // the sweep's cost model: N·t, or N³·t with interactions
    cost[e] = expected_run_seconds(make_problem(spec.experiments[e].scene.build()));
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost[a] > cost[b]; });
  std::vector<double> load(static_cast<std::size_t>(task.count), 0.0);
  std::vector<std::size_t> mine;
  for (const std::size_t e : order) {
    const std::size_t t = static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    load[t] += cost[e];
    if (t == task.index) mine.push_back(e);
  }
  std::sort(mine.begin(), mine.end());
  return mine;
}

}  // namespace asperity
