#include "io/arguments.hpp"

#include <algorithm>
#include <charconv>
#include <thread>

#include "io/input_error.hpp"

namespace asperity::io {

int hardware_threads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

std::string threads_problem(std::string_view text) {
  long long n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec == std::errc() && end == text.data() + text.size() && !text.empty() && n >= kMinThreads && n <= kMaxThreads)
    return {};
  return "Value " + std::string(text) + " not in range " + std::to_string(kMinThreads) + " to " +
         std::to_string(kMaxThreads);
}

int checked_threads(std::string_view text, const std::string& argument) {
  if (std::string why = threads_problem(text); !why.empty()) throw InputError("", 0, argument, why);
  int n = 0;
  std::from_chars(text.data(), text.data() + text.size(), n);
  return n;
}

void check_no_nul(std::string_view text, const std::string& argument) {
  const std::size_t at = text.find('\0');
  if (at == std::string_view::npos) return;
  std::string shown;
  for (const char c : text) shown += c == '\0' ? std::string("\\0") : std::string(1, c);
  throw InputError(shown, 0, argument,
                   "holds a NUL byte (character " + std::to_string(at + 1) + "), which would end the text there");
}

}  // namespace asperity::io
