#include "io/journal_line.hpp"

#include <charconv>
#include <cstdint>

#include "io/hash.hpp"

namespace asperity {

std::string journal_line(std::string_view row) {
  std::string line(row);
  line += ',';
  line += hex16(fnv1a64(row));
  line += '\n';
  return line;
}

bool checked_journal_row(std::string_view line, std::string_view& row) {
  const std::size_t comma = line.rfind(',');
  if (comma == std::string_view::npos || line.size() - comma - 1 != 16) return false;
  std::uint64_t sum = 0;
  const auto r = std::from_chars(line.data() + comma + 1, line.data() + line.size(), sum, 16);
  if (r.ec != std::errc() || r.ptr != line.data() + line.size()) return false;
  row = line.substr(0, comma);
  return fnv1a64(row) == sum;
}

}  // namespace asperity
