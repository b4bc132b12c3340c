#include "solve/interacting/solver_failure.hpp"

#include <cstdio>

#include "solve/core/run_info.hpp"

namespace asperity {

void interacting_solver_failure(const std::string& what, double X_m) {
  char msg[300];
  std::snprintf(msg, sizeof msg, "interacting event solver: %s at X = %.6g m", what.c_str(), X_m);
  throw SolverError(msg);
}

}  // namespace asperity
