#pragma once
// libgomp's thread pool does not survive fork(): the child has only the forking thread, and the
// next parallel region on it waits forever for pool threads that were not copied (Python's
// os.fork() after a run, multiprocessing's "fork" start method). Once guarded, the child runs the
// library's OpenMP regions on that thread single-threaded; the numbers do not change (the loops
// split their work in fixed blocks, adaptive_team.hpp). Threads the child starts later have
// pools of their own and keep their width.
namespace asperity {

// Registers the fork handler (pthread_atfork) once per process; cheap to call again. Called before
// the first OpenMP region a run opens (observe/simulate.cpp).
void guard_openmp_against_fork();

}  // namespace asperity
