// src/batch/: the parallel runner (every index once, progress counts, per-thread slots, a bounded
// ordered pipeline, rethrown exceptions), the stop flag, the journals' append file, the inputs.txt
// builder and the least-loaded dealing shared by the sweep's shards and the fit's tasks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "batch/inputs_fingerprint.hpp"
#include "batch/journal_file.hpp"
#include "batch/parallel_runner.hpp"
#include "batch/shard_plan.hpp"
#include "batch/stop_flag.hpp"
#include "io/journal_line.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using asperity::testing::fresh_dir;
using asperity::testing::slurp;
using asperity::testing::write_text;

TEST_CASE("parallel runner: every index once, progress counted to the end, slots below the thread count", "[batch]") {
  const ParallelRunner runner(3);
  CHECK(runner.threads() == 3);
  std::vector<std::atomic<int>> hits(500);
  std::atomic<std::size_t> last_done{0};
  std::mutex m;
  std::vector<std::size_t> done_counts;
  runner.for_each(
      hits.size(), [&](std::size_t i) { ++hits[i]; },
      [&](std::size_t finished, std::size_t total) {
        CHECK(total == hits.size());
        const std::lock_guard<std::mutex> lock(m);
        done_counts.push_back(finished);
        last_done = std::max<std::size_t>(last_done, finished);
      });
  CHECK(std::all_of(hits.begin(), hits.end(), [](const std::atomic<int>& h) { return h == 1; }));
  std::sort(done_counts.begin(), done_counts.end());
  CHECK(done_counts.size() == hits.size());
  CHECK(done_counts.front() == 1);
  CHECK(last_done == hits.size());

  std::vector<std::atomic<int>> covered(1000);
  std::atomic<bool> slot_ok{true};
  runner.for_each_range(covered.size(), 64, [&](std::size_t b, std::size_t e, int slot) {
    if (slot < 0 || slot >= runner.threads()) slot_ok = false;
    for (std::size_t i = b; i < e; ++i) ++covered[i];
  });
  CHECK(slot_ok);
  CHECK(std::all_of(covered.begin(), covered.end(), [](const std::atomic<int>& h) { return h == 1; }));
}

TEST_CASE("parallel runner: an exception of a body is rethrown; nested loops run inside a task", "[batch]") {
  const ParallelRunner runner(2);
  CHECK_THROWS_WITH(runner.for_each(10,
                                    [](std::size_t i) {
                                      if (i == 7) throw std::runtime_error("seven");
                                    }),
                    "seven");
  std::vector<std::atomic<int>> cells(4 * 25);
  runner.for_each(4, [&](std::size_t i) {
    for_each_nested(
        25, [&](std::size_t j) { ++cells[i * 25 + j]; }, i % 2 ? Nesting::isolated : Nesting::shared);
  });
  CHECK(std::all_of(cells.begin(), cells.end(), [](const std::atomic<int>& h) { return h == 1; }));
}

TEST_CASE("parallel runner pipeline: produced in order, worked in parallel, each consumed once, bounded", "[batch]") {
  struct Job {
    int index = 0, squared = 0;
  };
  const ParallelRunner runner(2);
  int next = 0;
  std::atomic<int> in_flight{0}, most{0};
  std::vector<int> consumed;
  runner.pipeline<Job>(
      [&]() -> std::shared_ptr<Job> {
        if (next == 200) return nullptr;
        auto j = std::make_shared<Job>();
        j->index = next++;
        const int now = ++in_flight;
        most = std::max(most.load(), now);
        return j;
      },
      [](Job& j) { j.squared = j.index * j.index; },
      [&](Job& j) {
        --in_flight;
        CHECK(j.squared == j.index * j.index);
        consumed.push_back(j.index);
      });
  std::sort(consumed.begin(), consumed.end());
  CHECK(consumed.size() == 200);
  for (int i = 0; i < 200; ++i) CHECK(consumed[static_cast<std::size_t>(i)] == i);
  CHECK(most <= 2 * runner.threads());
}

TEST_CASE("stop flag: no flag never stops and has no monitor; a set flag is seen by the monitor", "[batch]") {
  const StopFlag none;
  CHECK_FALSE(none.requested());
  CHECK(none.monitor() == nullptr);
  std::atomic<bool> flag{false};
  const StopFlag stop(&flag);
  REQUIRE(stop.monitor() != nullptr);
  CHECK(stop.monitor()->period_s == Approx(0.05));
  CHECK(stop.monitor()->poll(0, 1));
  CHECK_FALSE(stop.requested());
  flag = true;
  CHECK(stop.requested());
  CHECK_FALSE(stop.monitor()->poll(0, 1));
}

TEST_CASE("deal_by_cost: each item to the least loaded part, ties to the lower part", "[batch][shard]") {
  const std::vector<double> cost{5, 1, 1, 1, 1, 1, 3};
  std::vector<std::uint64_t> part(cost.size(), 99);
  const std::vector<double> load = deal_by_cost(
      cost.size(), 3, [&](std::uint64_t k) { return cost[k]; }, [&](std::uint64_t k, std::uint64_t p) { part[k] = p; });
  CHECK(part == std::vector<std::uint64_t>{0, 1, 2, 1, 2, 1, 2});
  CHECK(load == std::vector<double>{5, 3, 5});
  // Equal costs in index order: round robin exactly.
  const ShardPlan plan = ShardPlan::by_cost(io::Shard{1, 3}, 10, [](std::uint64_t) { return 2.0; });
  for (std::uint64_t i = 0; i < 10; ++i) CHECK(plan.contains(i) == (i % 3 == 1));
  CHECK(plan.size() == 3);
}

TEST_CASE("inputs fingerprint: the first line, build, slice, the caller's lines and files, byte for byte", "[batch]") {
  InputsFingerprint t("# kind", "asperity 1 commit abc", "shard", io::Shard{1, 4}, "cost-v1");
  t.add("set", "0123456789abcdef");
  t.add_file("", "a/b.yaml", [] { return std::uint64_t{0x1a2b}; });
  t.add_file("scene", "c.yaml", []() -> std::uint64_t { throw std::runtime_error("unreadable"); });
  CHECK(t.text() ==
        "# kind\nbuild asperity 1 commit abc\nshard 1/4 cost-v1\nset 0123456789abcdef\n"
        "file 0000000000001a2b a/b.yaml\nfile ---------------- scene c.yaml\n");
  CHECK(InputsFingerprint("# k", "b", "task", io::Shard{0, 1}).text() == "# k\nbuild b\ntask 0/1\n");
  const fs::path d = fresh_dir("asperity_batch_inputs");
  CHECK_FALSE(read_inputs(d));
  write_inputs(d, t.text());
  CHECK(read_inputs(d) == t.text());
  fs::remove_all(d);
}

TEST_CASE("journal file: checked lines appended, read back by offset, a torn tail cut", "[batch][journal]") {
  const fs::path d = fresh_dir("asperity_batch_journal");
  const fs::path file = write_text(d / "journal.csv", "a,b,sha256\n");
  {
    JournalFile j(file, true, "journal.csv");
    const std::size_t first = j.append("1,x");
    CHECK(first == io::journal_line("1,x").size());
    j.append("2,y");
    j.sync();
    CHECK(j.line_at(11) == io::journal_line("1,x").substr(0, first - 1));
    CHECK(io::journal_row(j.line_at(11 + first)) == "2,y");
  }
  const std::string good = slurp(file);
  write_text(file, good + "3,z,torn");
  {
    JournalFile j(file, false, "journal.csv");
    j.cut(good.size());
  }
  CHECK(slurp(file) == good);
  fs::remove_all(d);
}
