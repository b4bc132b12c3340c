#include "io/journal_line.hpp"

#include <charconv>
#include <cstdint>

#include "io/digest.hpp"
#include "io/hash.hpp"

namespace asperity::io {

std::string journal_line(std::string_view row) {
  std::string line(row);
  line += ',';
  line += sha256_hex(row);
  line += '\n';
  return line;
}

bool checked_journal_row(std::string_view line, std::string_view& row, JournalDigest digest) {
  const std::size_t comma = line.rfind(',');
  if (comma == std::string_view::npos) return false;
  const std::string_view sum = line.substr(comma + 1);
  const std::string_view r = line.substr(0, comma);
  if (digest == JournalDigest::sha256) {
    if (sum.size() != 64 || sum != sha256_hex(r)) return false;
  } else {
    std::uint64_t v = 0;
    if (sum.size() != 16) return false;
    const auto res = std::from_chars(sum.data(), sum.data() + sum.size(), v, 16);
    if (res.ec != std::errc() || res.ptr != sum.data() + sum.size() || fnv1a64(r) != v) return false;
  }
  row = r;
  return true;
}

std::string journal_header(std::string_view header) {
  std::string h(header);
  h += ',';
  h += kJournalDigestColumn;
  return h;
}

std::optional<JournalDigest> journal_digest_of(std::string_view first_line, std::string_view header) {
  if (first_line.size() <= header.size() || first_line.substr(0, header.size()) != header ||
      first_line[header.size()] != ',')
    return std::nullopt;
  const std::string_view column = first_line.substr(header.size() + 1);
  if (column == kJournalDigestColumn) return JournalDigest::sha256;
  if (column == kLegacyDigestColumn) return JournalDigest::fnv1a64_legacy;
  return std::nullopt;
}

std::string_view journal_row(std::string_view line) {
  const std::size_t comma = line.rfind(',');
  return comma == std::string_view::npos ? line : line.substr(0, comma);
}

}  // namespace asperity::io
