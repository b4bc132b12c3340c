#include "batch/stop_flag.hpp"

namespace asperity {

StopFlag::StopFlag(const std::atomic<bool>* flag) : flag_(flag) {
  if (!flag) return;
  monitor_.period_s = 0.05;
  monitor_.poll = [flag](double, double) { return !flag->load(std::memory_order_relaxed); };
}

}  // namespace asperity
