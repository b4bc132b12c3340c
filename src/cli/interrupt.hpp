#pragma once
// Ctrl-C as a request (sweep, fit): while an InterruptRequest lives, the first SIGINT only sets
// its flag, which the command hands to the batch (SweepOptions::stop, FitOptions::stop); the runs
// stop within ~0.05 s, the journal keeps what finished, and the command says so and exits 130.
// A second SIGINT ends the process at once, through the handler that was there before (main's:
// it removes our temporaries). SIGTERM is not caught here: a scheduler's stop stays immediate.
#include <atomic>
#include <csignal>

namespace asperity::cli {

class InterruptRequest {
 public:
  InterruptRequest();   // one at a time
  ~InterruptRequest();  // the previous SIGINT handler again
  InterruptRequest(const InterruptRequest&) = delete;
  InterruptRequest& operator=(const InterruptRequest&) = delete;

  const std::atomic<bool>* flag() const;
  bool requested() const { return flag()->load(); }
};

}  // namespace asperity::cli
