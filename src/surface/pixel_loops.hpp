#pragma once
// The loops over an n × n field of the FFT boundary-element solvers (surface/normal_contact.cpp,
// surface/tangential_contact.cpp): fixed blocks shared among a solve's threads, sums added in
// block order, so a result has the same bits whatever the number of threads.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace asperity::pixel_loops {

// Loops over the n² pixels, split among a solve's threads. Sums are taken over fixed blocks
// added in block order, so they have the same bits whatever the number of threads.
constexpr std::size_t kBlock = 1 << 14;
// Below this many points a loop runs on one thread: the threads' start and join would cost more
// than they save (and a thread waiting for a busy core stalls the others).
constexpr std::size_t kParallelFrom = std::size_t{1} << 18;

// The threads of one solve: a TBB task arena of `threads`. A loop is cut into fixed chunks, one
// task each, taken as threads come free: idle workers sleep instead of spinning at a barrier, and
// the caller takes chunks itself, so a worker that has lost its core on a machine shared with
// other work holds up at most the chunk it took (an OpenMP team, whose barriers wait for every
// thread and spin, was many times slower on a loaded machine: docs/performance.md). A chunk's
// values do not depend on the thread that computes it.
class Workers {
 public:
  explicit Workers(int threads) : count_(std::max(1, threads)), arena_(count_) {}
  int count() const { return count_; }

  // f(chunk, thread) for chunk = 0..chunks−1, thread < count(); on the caller alone if !parallel.
  template <class F>
  void run(std::size_t chunks, bool parallel, F&& f) {
    if (count_ == 1 || !parallel || chunks < 2) {
      for (std::size_t c = 0; c < chunks; ++c) f(c, std::size_t{0});
      return;
    }
    arena_.execute([&] {
      tbb::parallel_for(
          tbb::blocked_range<std::size_t>(0, chunks, 1),
          [&](const tbb::blocked_range<std::size_t>& r) {
            const auto t = static_cast<std::size_t>(tbb::this_task_arena::current_thread_index());
            for (std::size_t c = r.begin(); c != r.end(); ++c) f(c, t);
          },
          tbb::simple_partitioner());
    });
  }

 private:
  int count_;
  tbb::task_arena arena_;
};

template <class F>
void for_each_pixel(std::size_t count, Workers& w, F f) {
  w.run((count + kBlock - 1) / kBlock, count >= kParallelFrom, [&](std::size_t b, std::size_t) {
    const std::size_t begin = b * kBlock, end = std::min(count, begin + kBlock);
    for (std::size_t k = begin; k < end; ++k) f(k);
  });
}

// M sums at once: f(k, acc) adds pixel k's terms to acc[0..M).
template <std::size_t M, class F>
std::array<double, M> block_sums(std::size_t count, Workers& w, F f) {
  const std::size_t blocks = (count + kBlock - 1) / kBlock;
  std::vector<std::array<double, M>> part(blocks);
  w.run(blocks, count >= kParallelFrom, [&](std::size_t b, std::size_t) {
    std::array<double, M> acc{};
    const std::size_t begin = b * kBlock, end = std::min(count, begin + kBlock);
    for (std::size_t k = begin; k < end; ++k) f(k, acc);
    part[b] = acc;
  });
  std::array<double, M> total{};
  for (const auto& a : part)
    for (std::size_t i = 0; i < M; ++i) total[i] += a[i];
  return total;
}

}  // namespace asperity::pixel_loops
