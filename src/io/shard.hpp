#pragma once
// One slice of a job split into N parts: a sweep's `--shard I/N` (points with index % N == I) and
// a fit's `--task I/N` (its share of the per-experiment optimizations). Parses "I/N" (0 <= I < N),
// or "auto": the task of a SLURM job array (I = SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN,
// N = SLURM_ARRAY_TASK_COUNT; the array must be contiguous, e.g. --array=0-15), read through `env`
// (default std::getenv); std::invalid_argument with a one-line message naming `option` otherwise.
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <string>

namespace asperity::io {

struct Shard {
  std::uint64_t index = 0, count = 1;
  bool contains(std::uint64_t point) const { return point % count == index; }
  std::uint64_t size(std::uint64_t total) const {  // points of this shard among `total`
    return total / count + (index < total % count ? 1 : 0);
  }
};

Shard parse_shard(
    const std::string& text,
    const std::function<const char*(const char*)>& env = [](const char* n) { return std::getenv(n); },
    const std::string& option = "--shard");

}  // namespace asperity::io
