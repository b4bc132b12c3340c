#pragma once
// The one parallel runner of the many-run commands (sweep, fit, reproduce, claim variants,
// regress): a TBB task arena of a fixed number of threads, so a batch never takes more cores than
// asked whatever else the process runs. Every task is a whole model run (milliseconds to hours),
// so loops hand out one index at a time (no chunking: uneven run times balance) unless a grain
// is given. The caller's results go by index into its own storage: what a batch computes never
// depends on the thread count or on which thread ran what. TBB stays behind this header.
#include <cstddef>
#include <functional>
#include <memory>

namespace asperity {

class ParallelRunner {
 public:
  explicit ParallelRunner(int threads);  // <= 0: every hardware thread
  ~ParallelRunner();
  ParallelRunner(const ParallelRunner&) = delete;
  ParallelRunner& operator=(const ParallelRunner&) = delete;

  int threads() const { return threads_; }

  // body(i) for every i in [0, n), each once, on the runner's threads; then, when given,
  // done(finished, n) with the count finished so far (thread-safe: for a progress line). The
  // first exception of a body is rethrown here once the others have ended.
  void for_each(std::size_t n, const std::function<void(std::size_t)>& body,
                const std::function<void(std::size_t, std::size_t)>& done = {}) const;

  // body(begin, end, slot) over ranges of about `grain` indices of [0, n) (cheap bodies); `slot`
  // (< threads()) names the thread, for per-thread state kept by the caller without a lock.
  void for_each_range(std::size_t n, std::size_t grain,
                      const std::function<void(std::size_t, std::size_t, int)>& body) const;

  // A pipeline of three stages with at most 2·threads() jobs in flight (memory does not grow with
  // the batch): produce() on one thread at a time, in order, until it returns null; work(job) in
  // parallel; consume(job) on one thread at a time, in the order the jobs finish.
  template <class Job>
  void pipeline(const std::function<std::shared_ptr<Job>()>& produce, const std::function<void(Job&)>& work,
                const std::function<void(Job&)>& consume) const {
    run_pipeline([&]() -> std::shared_ptr<void> { return produce(); },
                 [&](void* job) { work(*static_cast<Job*>(job)); },
                 [&](void* job) { consume(*static_cast<Job*>(job)); });
  }

 private:
  void run_pipeline(const std::function<std::shared_ptr<void>()>& produce, const std::function<void(void*)>& work,
                    const std::function<void(void*)>& consume) const;
  struct Arena;
  std::unique_ptr<Arena> arena_;
  int threads_;
};

// Whether a thread waiting on a nested loop may pick up other tasks of its runner meanwhile.
// isolated: only this loop's (a fit's evaluation: each optimizer stays on its own stack).
enum class Nesting { shared, isolated };

// Inside a task of a runner: body(i) for i in [0, n) in parallel on the same runner's threads.
void for_each_nested(std::size_t n, const std::function<void(std::size_t)>& body, Nesting nesting = Nesting::shared);

}  // namespace asperity
