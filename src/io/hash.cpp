#include "io/hash.hpp"

namespace asperity::io {

std::uint64_t fnv1a64_extend(std::uint64_t h, std::string_view more) {
  for (const unsigned char c : more) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::uint64_t fnv1a64(std::string_view bytes) { return fnv1a64_extend(14695981039346656037ull, bytes); }

std::string hex16(std::uint64_t h) {
  static const char* digits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) s[static_cast<std::size_t>(i)] = digits[h & 0xf];
  return s;
}

}  // namespace asperity::io
