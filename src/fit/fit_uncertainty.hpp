#pragma once
// What run_fit computes around an optimization's optimum, beside the optimizer (fit.hpp:
// Optimization::profiles, uncertainty, refits): the objective's profiles, its Hessian with the
// covariance and marginal standard deviations it gives, and the error-bar refits. Internal to fit/.
#include <atomic>

#include "fit/fit.hpp"
#include "fit/fit_problem.hpp"

namespace asperity::fit_detail {

// The objective along each profiled parameter around the optimum, the others at the optimum
// (in parallel, journaled; points of every profile share the part "profile": their values differ).
void run_profile(const FitSpec& spec, const Problem& pb, Optimization& o);

// The Hessian of the objective at the optimum by central differences in the scaled coordinates,
// its covariance and the marginal standard deviations (fit.hpp, Uncertainty).
// Also the profiles' conditional intervals at the same rise s².
void run_uncertainty(const FitSpec& spec, const Problem& pb, Optimization& o);

// The parametric bootstrap (FitSpec::bootstrap_draws): each draw's synthetic data from the
// optimum's runs (Optimization::best_runs) plus noise, refitted by the local stage from the
// optimum (in parallel, journaled as part "bootstrap K"); fit_bootstrap.cpp.
void run_bootstrap(const FitSpec& spec, const Problem& pb, Optimization& o);

// The refits with each error-bar key shifted by -bar and +bar (in parallel, journaled).
void run_refits(const FitSpec& spec, const FitOptions& options, Optimization& o, Counts& counts, const StopFlag& stop,
                std::atomic<int>& ticked);

}  // namespace asperity::fit_detail
