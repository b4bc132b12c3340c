#pragma once
// The result store of a campaign, a folder (results/<campaign>/ by default):
//   journal.csv     append-only, the truth: a header, then one line per finished point, each
//                   line = the points.csv row + "," + FNV-1a 64 of that row (16 hex digits).
//                   Appended with write() + fdatasync() by one thread, so after kill -9 at any
//                   instant the file is good lines followed by at most one torn last line,
//                   which the checksum detects and the next run drops (and recomputes).
//   points.csv      the rows of the journal sorted by point index, one per point (latest wins),
//                   written atomically (temp + rename) at the end of every run and by merge.
//   provenance.yaml campaign file and its hash, project version, build type, date: written once.
//   campaign.yaml   a copy of the campaign file as it was when the store was started.
//   series/HASH.csv optional per-point series (campaign `series: true`).
//   .lock           flock: one sweep per store at a time.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace asperity {

// FNV-1a 64-bit (offset basis 14695981039346656037, prime 1099511628211): stable across runs,
// machines and library versions, unlike std::hash / boost::hash.
std::uint64_t fnv1a64(std::string_view bytes);
std::string hex16(std::uint64_t h);  // 16 lowercase hex digits

// CSV fields: quoted ("..." with "" escapes) when they hold ',', '"' or blanks at the ends;
// newlines become spaces (one line per row, always).
std::string csv_field(std::string_view s);
// Splits one CSV line (RFC 4180 quoting). Throws std::runtime_error on an unterminated quote.
std::vector<std::string> csv_split(std::string_view line);

struct JournalEntry {
  std::uint64_t hash = 0;       // canonical scene hash of the point
  bool ok = false;              // status == ok
  std::uint64_t offset = 0;     // byte offset of the row in journal.csv
  std::uint32_t length = 0;     // row length (without checksum and newline)
};

// Opens (creating when absent) DIR/journal.csv for appending, after recovering it: lines with a
// bad checksum and a torn last line are dropped (the file is rewritten atomically without them).
// A store holding points.csv but no journal (a committed store) is seeded from points.csv.
// A header different from `header` (another campaign or version) → std::runtime_error.
class Journal {
 public:
  Journal(const std::filesystem::path& dir, const std::string& header);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  std::size_t dropped_lines() const { return dropped_; }  // found torn or corrupt at open
  const std::map<std::uint64_t, JournalEntry>& entries() const { return entries_; }  // by index

  // Appends one row (no newline; first field the index, second the hash in hex, a `status`
  // column as in the header) durably (write + fdatasync). Not thread-safe: one writer, and
  // entries() must not be read concurrently.
  void append(const std::string& row);

  // The row text of an entry.
  std::string row(const JournalEntry& e) const;

  // Writes DIR/points.csv atomically: header + rows of the entries whose index `keep(index)`.
  template <class Keep>
  void write_points(const std::filesystem::path& dir, Keep keep) const;

  static std::size_t status_column(const std::string& header);

 private:
  void add_entry(const std::string& row, std::uint64_t offset);
  void write_points_impl(const std::filesystem::path& dir, const std::vector<const JournalEntry*>& rows) const;
  std::string header_;
  std::size_t status_col_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::size_t dropped_ = 0;
  std::map<std::uint64_t, JournalEntry> entries_;
};

template <class Keep>
void Journal::write_points(const std::filesystem::path& dir, Keep keep) const {
  std::vector<const JournalEntry*> rows;
  for (const auto& [index, e] : entries_)
    if (keep(index)) rows.push_back(&e);
  write_points_impl(dir, rows);
}

// Writes `text` to `path` atomically (temp sibling, fsync, rename, fsync of the folder).
void write_file_durably(const std::filesystem::path& path, const std::string& text);

// Reads a whole file (std::runtime_error when it cannot).
std::string read_file_text(const std::filesystem::path& path);

// The journal's valid rows of DIR (read-only: for merge and plot of unfinished stores); the
// rows of points.csv when the store has no journal.
struct StoreRows {
  std::string header;                     // points.csv header
  std::map<std::uint64_t, std::string> rows;  // index → row text
};
StoreRows read_store(const std::filesystem::path& dir);

// An exclusive lock on DIR/.lock held for the object's lifetime (std::runtime_error when another
// process holds it).
class StoreLock {
 public:
  explicit StoreLock(const std::filesystem::path& dir);
  ~StoreLock();
  StoreLock(const StoreLock&) = delete;
  StoreLock& operator=(const StoreLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace asperity
