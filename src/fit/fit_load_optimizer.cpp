#include "fit/fit_load_optimizer.hpp"

#include <nlopt.hpp>

#include <stdexcept>
#include <vector>

#include "fit/fit_load.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"

namespace asperity {

using io::format_double;
using io::MapView;
using io::quote;
using io::Source;

namespace {

const std::vector<std::string> kOptimizerKeys{"algorithm",       "xtol_rel",       "ftol_rel", "ftol_abs",
                                              "max_evaluations", "initial_step",   "polish",   "starts",
                                              "basin_tolerance", "basin_distance", "certify"};
const std::vector<std::string> kPolishKeys{"algorithm", "max_evaluations"};

// optimizer.{starts, basin_tolerance, basin_distance, certify} into spec (after the algorithm and polish:
// further starts need a local stage).
void read_starts(const MapView& o, FitSpec& spec) {
  if (auto n = o.find("starts")) {
    spec.starts = o.integer(*n, "starts");
    if (spec.starts < 1 || spec.starts > kMaxFitStarts)
      o.fail_at(*n, "starts",
                "must be in [1, " + std::to_string(kMaxFitStarts) + "], got " + std::to_string(spec.starts));
    if (spec.starts > 1 && spec.polish_algorithm.empty() && spec.algorithm.rfind("LN_", 0) != 0)
      o.fail_at(*n, "starts",
                "every start after the first runs the local stage, and " + quote(spec.algorithm) +
                    " is global with no polish: add polish: {algorithm: LN_SBPLX} or use an LN_* algorithm");
  }
  if (auto n = o.find("certify")) spec.certify = o.boolean(*n, "certify");
  if (auto n = o.find("basin_tolerance")) {
    spec.basin_tolerance = o.number(*n, "basin_tolerance", nullptr);
    if (!(spec.basin_tolerance >= 0 && spec.basin_tolerance < 1))
      o.fail_at(*n, "basin_tolerance",
                "must be in [0, 1) (relative to the best objective), got " + format_double(spec.basin_tolerance));
  }
  if (auto n = o.find("basin_distance")) {
    spec.basin_distance = o.number(*n, "basin_distance", nullptr);
    if (!(spec.basin_distance >= 0 && spec.basin_distance < 1))
      o.fail_at(*n, "basin_distance",
                "must be in [0, 1) (in the scaled coordinates, each parameter's range 1), got " +
                    format_double(spec.basin_distance));
  }
}

}  // namespace

// `optimizer:` into spec; the node that named the algorithm (undefined: none).
YAML::Node read_optimizer(const Source& src, const MapView& root, FitSpec& spec) {
  YAML::Node algorithm_node;
  const auto on = root.find("optimizer");
  if (!on) return algorithm_node;
  const MapView o(src, *on, "optimizer", kOptimizerKeys);
  if (auto n = o.find("algorithm")) {
    spec.algorithm = o.string(*n, "algorithm");
    if (const std::string why = check_fit_algorithm(spec.algorithm); !why.empty()) o.fail_at(*n, "algorithm", why);
    algorithm_node = *n;
  }
  if (auto n = o.find("xtol_rel")) {
    spec.xtol_rel = o.number(*n, "xtol_rel", nullptr);
    if (!(spec.xtol_rel > 0 && spec.xtol_rel < 1))
      o.fail_at(*n, "xtol_rel", "must be in (0, 1), got " + format_double(spec.xtol_rel));
  }
  if (auto n = o.find("ftol_rel")) {
    spec.ftol_rel = o.number(*n, "ftol_rel", nullptr);
    if (!(spec.ftol_rel >= 0 && spec.ftol_rel < 1))
      o.fail_at(*n, "ftol_rel", "must be in [0, 1) (0: off), got " + format_double(spec.ftol_rel));
  }
  if (auto n = o.find("ftol_abs")) {
    spec.ftol_abs = o.number(*n, "ftol_abs", nullptr);
    if (!(spec.ftol_abs >= 0)) o.fail_at(*n, "ftol_abs", "must be >= 0 (0: off), got " + format_double(spec.ftol_abs));
  }
  if (auto n = o.find("max_evaluations")) {
    spec.max_evaluations = o.integer(*n, "max_evaluations");
    if (spec.max_evaluations < 1)
      o.fail_at(*n, "max_evaluations", "must be >= 1, got " + std::to_string(spec.max_evaluations));
  }
  if (auto pn = o.find("polish")) {
    const MapView pv(src, *pn, "optimizer.polish", kPolishKeys);
    const YAML::Node an = pv.require("algorithm");
    spec.polish_algorithm = pv.string(an, "algorithm");
    if (const std::string why = check_fit_algorithm(spec.polish_algorithm); !why.empty())
      pv.fail_at(an, "algorithm", why);
    if (spec.polish_algorithm.rfind("LN_", 0) != 0)
      pv.fail_at(an, "algorithm",
                 "the polish stage is local: use an LN_* algorithm, got " + quote(spec.polish_algorithm));
    if (auto n = pv.find("max_evaluations")) {
      spec.polish_max_evaluations = pv.integer(*n, "max_evaluations");
      if (spec.polish_max_evaluations < 1)
        pv.fail_at(*n, "max_evaluations", "must be >= 1, got " + std::to_string(spec.polish_max_evaluations));
    }
  }
  if (auto n = o.find("initial_step")) {
    spec.initial_step = o.number(*n, "initial_step", nullptr);
    if (!(spec.initial_step > 0 && spec.initial_step <= 1))
      o.fail_at(
          *n, "initial_step",
          "must be in (0, 1] (a fraction of each parameter's scaled range), got " + format_double(spec.initial_step));
  }
  read_starts(o, spec);
  return algorithm_node;
}

// The algorithm must accept this many variables (e.g. LN_NEWUOA_BOUND needs ≥ 2): a 3-evaluation trial.
void check_algorithm_accepts(const FitSpec& spec, const MapView& root, const YAML::Node& algorithm_node,
                             const std::string& display) {
  std::size_t n = 0;
  for (const auto& p : spec.parameters) n += (p.per_experiment && !spec.separate) ? spec.experiments.size() : 1;
  try {
    nlopt::opt trial(static_cast<nlopt::algorithm>(nlopt_algorithm_from_string(spec.algorithm.c_str())),
                     static_cast<unsigned>(n));
    trial.set_lower_bounds(std::vector<double>(n, 0.0));
    trial.set_upper_bounds(std::vector<double>(n, 1.0));
    trial.set_min_objective(
        [](unsigned m, const double* x, double*, void*) {
          double s = 0;
          for (unsigned i = 0; i < m; ++i) s += (x[i] - 0.3) * (x[i] - 0.3);
          return s;
        },
        nullptr);
    trial.set_maxeval(3);
    std::vector<double> x(n, 0.5);
    double f = 0;
    trial.optimize(x, f);
  } catch (const std::invalid_argument& e) {
    const std::string msg =
        "NLopt rejects " + spec.algorithm + " with " + std::to_string(n) + " free variable(s): " + e.what();
    if (algorithm_node.IsDefined()) root.fail_at(algorithm_node, "optimizer.algorithm", msg);
    throw io::InputError(display, 0, "optimizer.algorithm", msg);
  } catch (const std::exception&) {
    // Other stops of a 3-evaluation trial (e.g. roundoff) say nothing about the input.
  }
}

}  // namespace asperity
