#include "cli/interrupt.hpp"

#include <signal.h>

namespace asperity::cli {
namespace {

// Process-wide, as a signal handler needs; a lock-free atomic is safe to set from one.
std::atomic<bool> g_requested{false};
struct sigaction g_previous {};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int sig) {
  if (!g_requested.exchange(true)) return;
  // The second Ctrl-C: the handler that was there before, at once.
  ::sigaction(sig, &g_previous, nullptr);
  ::raise(sig);
}

}  // namespace

InterruptRequest::InterruptRequest() {
  g_requested.store(false);
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sa.sa_flags = SA_RESTART;  // reads and writes in progress go on; the batch polls the flag
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, &g_previous);
}

InterruptRequest::~InterruptRequest() { ::sigaction(SIGINT, &g_previous, nullptr); }

const std::atomic<bool>* InterruptRequest::flag() const { return &g_requested; }

}  // namespace asperity::cli
