#pragma once
// The line format of the append-only journals (a sweep store's journal.csv, a fit's journal.csv):
// "ROW,CHECKSUM\n", CHECKSUM the FNV-1a 64 of ROW in 16 hex digits. Each line is appended with one
// write(), so after kill -9 a journal is whole lines plus at most one torn last line; the checksum
// tells a torn or damaged line from a good one.
#include <string>
#include <string_view>

namespace asperity {

// ROW + "," + checksum + "\n".
std::string journal_line(std::string_view row);

// A journal line without its newline → its ROW when the checksum matches (false otherwise).
bool checked_journal_row(std::string_view line, std::string_view& row);

}  // namespace asperity
