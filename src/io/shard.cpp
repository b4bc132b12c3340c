#include "io/shard.hpp"

#include <charconv>
#include <stdexcept>

namespace asperity::io {

namespace {

// A non-negative whole number from the environment variable `name`.
std::uint64_t slurm_number(const std::function<const char*(const char*)>& env, const char* name,
                           const std::string& option) {
  const char* v = env(name);
  const std::string text = v ? v : "";
  std::uint64_t n = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), n);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size())
    throw std::invalid_argument(
        option + " auto: " + name +
        (v ? " is '" + text + "', not a whole number" : " is not set (not inside a SLURM job array?)"));
  return n;
}

}  // namespace

Shard parse_shard(const std::string& text, const std::function<const char*(const char*)>& env,
                  const std::string& option) {
  if (text == "auto") {
    const std::uint64_t id = slurm_number(env, "SLURM_ARRAY_TASK_ID", option),
                        lo = slurm_number(env, "SLURM_ARRAY_TASK_MIN", option),
                        hi = slurm_number(env, "SLURM_ARRAY_TASK_MAX", option),
                        count = slurm_number(env, "SLURM_ARRAY_TASK_COUNT", option);
    if (hi < lo || hi - lo + 1 != count || id < lo || id > hi)
      throw std::invalid_argument(option + " auto: the job array must be contiguous (e.g. --array=0-15); got tasks " +
                                  std::to_string(lo) + "-" + std::to_string(hi) + ", " + std::to_string(count) +
                                  " of them, this one " + std::to_string(id));
    return Shard{id - lo, count};
  }
  const auto bad = [&] {
    return std::invalid_argument(option + " " + text +
                                 ": expected I/N with 0 <= I < N, e.g. 0/4, or auto (a SLURM array task)");
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) throw bad();
  Shard s;
  const char* b = text.data();
  const char* e = b + text.size();
  auto r1 = std::from_chars(b, b + slash, s.index);
  auto r2 = std::from_chars(b + slash + 1, e, s.count);
  if (r1.ec != std::errc() || r1.ptr != b + slash || r2.ec != std::errc() || r2.ptr != e || slash == 0 ||
      s.count == 0 || s.index >= s.count)
    throw bad();
  return s;
}

}  // namespace asperity::io
