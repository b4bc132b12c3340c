#pragma once
// The one way the fast interacting solver reports that it cannot go on: a SolverError naming
// what failed and the slider position X [m] where.
#include <string>

namespace asperity {

[[noreturn]] void interacting_solver_failure(const std::string& what, double X_m);

}  // namespace asperity
