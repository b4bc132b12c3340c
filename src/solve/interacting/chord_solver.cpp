// ChordSolver over the dense pinned operator, compiled once here (chord_solver.hpp declares it
// extern); the definitions are chord_solver_impl.hpp's.
#include "solve/interacting/chord_solver_impl.hpp"

namespace asperity {

template class ChordSolver<PinnedCompliance>;

}  // namespace asperity
