#pragma once
// The line format of the append-only journals (a sweep store's journal.csv, a fit's journal.csv):
// "ROW,DIGEST\n", DIGEST the SHA-256 of ROW in 64 hex digits (io/digest.hpp). Each line is
// appended with one write(), so after kill -9 a journal is whole lines plus at most one torn last
// line; the digest tells a torn, damaged or spliced line from a good one. The header's last
// column names the digest: "sha256"; journals written before it ("check") carry the FNV-1a 64 of
// each row in 16 hex digits and are read as such, then rewritten with SHA-256 when appended to.
#include <optional>
#include <string>
#include <string_view>

namespace asperity::io {

enum class JournalDigest { sha256, fnv1a64_legacy };

inline constexpr std::string_view kJournalDigestColumn = "sha256";
inline constexpr std::string_view kLegacyDigestColumn = "check";

// ROW + "," + SHA-256 + "\n".
std::string journal_line(std::string_view row);

// A journal line without its newline → its ROW when its digest (of kind `digest`) matches.
bool checked_journal_row(std::string_view line, std::string_view& row, JournalDigest digest = JournalDigest::sha256);

// The header line of a journal whose rows have the columns `header`: header + ",sha256".
std::string journal_header(std::string_view header);

// Which digest a journal's first line announces for rows with the columns `header`; nothing when
// it is another header.
std::optional<JournalDigest> journal_digest_of(std::string_view first_line, std::string_view header);

// The row of a line known to be good (the text before its last comma).
std::string_view journal_row(std::string_view line);

}  // namespace asperity::io
