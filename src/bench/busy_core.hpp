#pragma once
// Another process keeping one core busy (a plain loop, as a user's other job would), for
// benchmarks of a loaded machine: started by the constructor, killed by the destructor. It ends
// by itself after limit_s seconds, or when this process dies, so it cannot outlive a benchmark.
#include <sys/types.h>

namespace asperity {

class BusyCore {
 public:
  explicit BusyCore(unsigned limit_s);
  ~BusyCore();
  BusyCore(const BusyCore&) = delete;
  BusyCore& operator=(const BusyCore&) = delete;

 private:
  pid_t pid_ = -1;
};

}  // namespace asperity
