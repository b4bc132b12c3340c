#include "regress/regress.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "batch/parallel_runner.hpp"
#include "observe/simulate.hpp"
#include "scene/load.hpp"

namespace asperity {

std::map<std::string, double> regress_observables(const Observables& o) {
  return {{"Q_s", o.Q_s},
          {"A_s", o.A_s},
          {"t_peak", o.t_peak},
          {"alpha", o.alpha},
          {"shape_exponent", o.shape_exponent},
          {"area_drop_fraction", o.area_drop_fraction},
          {"ss_cycles", static_cast<double>(o.ss_cycles)},
          {"ss_drop", o.ss_drop},
          {"ss_period", o.ss_period},
          {"n_peaks", static_cast<double>(o.n_peaks)},
          {"t_end", o.t_end}};
}

bool regress_is_count(const std::string& name) { return name == "ss_cycles" || name == "n_peaks"; }

std::vector<RegressResult> run_regress_suite(const RegressSuite& suite, bool tight, int threads) {
  const std::size_t n = suite.entries.size();
  std::vector<RegressResult> out(n);
  std::vector<Scene> scenes(n);
  // Load on this thread: a bad scene is an input error of the suite, not a failed entry.
  for (std::size_t i = 0; i < n; ++i) {
    scenes[i] = load_scene(suite.entries[i].scene, suite.entries[i].overrides);
    out[i].name = suite.entries[i].name;
    const bool ref = scenes[i].solver.method == SolverMethod::reference;
    out[i].solver_rel_floor = ref ? 1e-12 : 10 * scenes[i].solver.tolerance;
  }
  const std::size_t jobs = tight ? 2 * n : n;
  ParallelRunner(std::max(1, threads)).for_each(jobs, [&](std::size_t j) {
    const std::size_t i = j % n;
    const bool twin = j >= n;
    Scene s = scenes[i];
    s.output.series.clear();
    if (twin) {
      if (s.solver.method == SolverMethod::reference)
        s.solver.Ct *= 2;
      else {
        s.solver.tolerance = std::max(1e-13, s.solver.tolerance * 1e-2);
        s.solver.interaction_tolerance = std::max(1e-14, s.solver.interaction_tolerance * 1e-2);
      }
    }
    try {
      const RunResult r = simulate(s);
      (twin ? out[i].tight : out[i].values) = regress_observables(r.obs);
      if (!twin) out[i].wall_s = r.obs.wall_s;
    } catch (const std::exception& e) {
      out[i].error = std::string(twin ? "tightened twin: " : "") + e.what();
    }
  });
  return out;
}

Golden bless(const std::vector<RegressResult>& results, std::vector<GoldenRecord> history) {
  Golden g;
  g.history = std::move(history);
  for (const auto& r : results) {
    if (!r.error.empty()) throw std::runtime_error("cannot bless: " + r.name + " failed: " + r.error);
    for (const auto& [key, v] : r.values) {
      const auto it = r.tight.find(key);
      const double vt = it == r.tight.end() ? v : it->second;
      double tol;
      if (regress_is_count(key)) {
        tol = std::isfinite(vt) ? std::abs(v - vt) : 0.0;
      } else if (std::isnan(v)) {
        tol = 0;
      } else {
        const double d = std::isfinite(vt) ? std::abs(v - vt) : std::abs(v);
        tol = std::max(10 * d, r.solver_rel_floor * std::abs(v));
      }
      g.entries[r.name][key] = GoldenValue{v, tol};
    }
  }
  return g;
}

std::vector<Drift> compare(const Golden& golden, const std::vector<RegressResult>& results) {
  std::vector<Drift> rows;
  for (const auto& r : results) {
    const auto ge = golden.entries.find(r.name);
    if (!r.error.empty()) {
      rows.push_back({r.name, "(run)", 0, 0, 0, false, "run failed: " + r.error});
      continue;
    }
    if (ge == golden.entries.end()) {
      rows.push_back({r.name, "(entry)", 0, 0, 0, false, "not in golden: bless it with --update"});
      continue;
    }
    for (const auto& [key, v] : r.values) {
      const auto gv = ge->second.find(key);
      if (gv == ge->second.end()) {
        rows.push_back({r.name, key, 0, v, 0, false, "not in golden"});
        continue;
      }
      Drift d{r.name, key, gv->second.value, v, gv->second.tolerance, true, ""};
      if (std::isnan(d.golden) || std::isnan(v)) {
        d.ok = std::isnan(d.golden) && std::isnan(v);
        if (!d.ok) d.note = "NaN on one side";
      } else {
        d.ok = std::abs(v - d.golden) <= d.tolerance;
      }
      rows.push_back(d);
    }
  }
  for (const auto& entry : golden.entries) {
    const std::string& name = entry.first;  // (clang 14 cannot capture structured bindings)
    const bool ran =
        std::any_of(results.begin(), results.end(), [&](const RegressResult& r) { return r.name == name; });
    if (!ran) rows.push_back({name, "(entry)", 0, 0, 0, false, "in golden but not in the suite"});
  }
  return rows;
}

}  // namespace asperity
