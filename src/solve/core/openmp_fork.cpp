#include "solve/core/openmp_fork.hpp"

#include <omp.h>
#include <pthread.h>

#include <mutex>

namespace asperity {

namespace {

// In the child, on the thread that called fork(): its OpenMP regions get one thread, which needs
// no pool (glibc has reset malloc's locks before child handlers run, so libgomp may allocate).
extern "C" void openmp_one_thread_in_child() { omp_set_num_threads(1); }

}  // namespace

void guard_openmp_against_fork() {
  static std::once_flag once;
  std::call_once(once, [] { ::pthread_atfork(nullptr, nullptr, openmp_one_thread_in_child); });
}

}  // namespace asperity
