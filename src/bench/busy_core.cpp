#include "bench/busy_core.hpp"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <stdexcept>

namespace asperity {

BusyCore::BusyCore(unsigned limit_s) {
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) throw std::runtime_error("bench: cannot start the busy-loop process");
  if (pid_ == 0) {
    // The child of a threaded process: async-signal-safe calls only, then the loop.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(0);
    alarm(limit_s);
    for (volatile unsigned long i = 0;; i = i + 1) {
    }
  }
}

BusyCore::~BusyCore() {
  if (pid_ <= 0) return;
  kill(pid_, SIGKILL);
  int status = 0;
  waitpid(pid_, &status, 0);
}

}  // namespace asperity
