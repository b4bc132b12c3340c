#pragma once
// The durable append side of the journals of a batch (a sweep store's journal.csv, a fit's
// journal.csv): a header, then one checked line per finished item (io/journal_line.hpp: "ROW,
// SHA-256"), each appended with one write(), so after kill -9 at any instant the file is good
// lines plus at most one torn last line. When to fdatasync is the caller's policy (a fit after
// every evaluation, a sweep per group of points); what a journal's rows mean is the caller's too.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace asperity {

// The line of the open file `fd` that starts at byte `offset`, without its newline (pread:
// thread-safe); std::runtime_error naming `name` when the line has no newline.
std::string read_line_at(int fd, std::uint64_t offset, const std::string& name);

class JournalFile {
 public:
  // Opens `path` (a regular file, no link followed: io/safe_open.hpp; InputError key "--out")
  // for appending, and for pread when `readable`. `name`: how messages name the file.
  // std::runtime_error "cannot open PATH: ..." otherwise.
  JournalFile(const std::filesystem::path& path, bool readable, std::string name);
  ~JournalFile();  // closes, without a sync (a caller syncs what it promised)
  JournalFile(const JournalFile&) = delete;
  JournalFile& operator=(const JournalFile&) = delete;

  // Appends the checked line of `row` (no newline) with one write(); returns its length in bytes
  // (std::runtime_error "cannot write NAME: ..." on failure).
  std::size_t append(std::string_view row);
  // append() then fdatasync, either failing as "cannot write NAME: ..." (a fit's evaluation: the
  // line is durable before the next one is asked for).
  void append_durably(std::string_view row);
  void sync();               // fdatasync (std::runtime_error "cannot sync NAME: ...")
  bool try_sync() noexcept;  // the same for a destructor: false when it failed
  // Cuts the file to its first `size` bytes (a torn or damaged tail after the last good line).
  void cut(std::uint64_t size);
  // The line that starts at byte `offset`, without its newline (pread: thread-safe).
  std::string line_at(std::uint64_t offset) const { return read_line_at(fd_, offset, name_); }

 private:
  std::string name_;
  int fd_ = -1;
};

}  // namespace asperity
