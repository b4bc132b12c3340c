#include "batch/parallel_runner.hpp"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <atomic>

namespace asperity {

struct ParallelRunner::Arena {
  tbb::task_arena arena;
};

ParallelRunner::ParallelRunner(int threads) : threads_(threads > 0 ? threads : tbb::info::default_concurrency()) {
  arena_ = std::make_unique<Arena>();
  arena_->arena.initialize(threads_);
}

ParallelRunner::~ParallelRunner() = default;

void ParallelRunner::for_each(std::size_t n, const std::function<void(std::size_t)>& body,
                              const std::function<void(std::size_t, std::size_t)>& done) const {
  std::atomic<std::size_t> finished{0};
  arena_->arena.execute([&] {
    tbb::parallel_for(
        std::size_t{0}, n,
        [&](std::size_t i) {
          body(i);
          if (done) done(++finished, n);
        },
        tbb::simple_partitioner());
  });
}

void ParallelRunner::for_each_range(std::size_t n, std::size_t grain,
                                    const std::function<void(std::size_t, std::size_t, int)>& body) const {
  arena_->arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
      body(r.begin(), r.end(), tbb::this_task_arena::current_thread_index());
    });
  });
}

void ParallelRunner::run_pipeline(const std::function<std::shared_ptr<void>()>& produce,
                                  const std::function<void(void*)>& work,
                                  const std::function<void(void*)>& consume) const {
  using Job = std::shared_ptr<void>;
  auto first = [&](tbb::flow_control& fc) -> Job {
    Job job = produce();
    if (!job) fc.stop();
    return job;
  };
  auto middle = [&](Job job) -> Job {
    work(job.get());
    return job;
  };
  auto last = [&](Job job) { consume(job.get()); };
  arena_->arena.execute([&] {
    tbb::parallel_pipeline(static_cast<std::size_t>(2 * threads_),
                           tbb::make_filter<void, Job>(tbb::filter_mode::serial_in_order, first) &
                               tbb::make_filter<Job, Job>(tbb::filter_mode::parallel, middle) &
                               tbb::make_filter<Job, void>(tbb::filter_mode::serial_out_of_order, last));
  });
}

void for_each_nested(std::size_t n, const std::function<void(std::size_t)>& body, Nesting nesting) {
  // An isolated context: when a sibling task of the enclosing loop throws (a stop's
  // RunInterrupted), TBB cancels that loop's context and, through it, every bound child context,
  // whose bodies would then be skipped without a word: an evaluation whose runs never ran,
  // scored as NaN and journaled as a failure. Isolated, this loop runs every body or throws.
  auto loop = [&] {
    tbb::task_group_context context(tbb::task_group_context::isolated);
    tbb::parallel_for(std::size_t{0}, n, body, context);
  };
  if (nesting == Nesting::isolated)
    tbb::this_task_arena::isolate(loop);
  else
    loop();
}

}  // namespace asperity
