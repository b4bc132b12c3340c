#pragma once
// The one way the project writes a file: the text goes to a hidden temporary sibling (temp_name:
// ".NAME.tmp-HOST-PID-N", a name no user file has and that the store and output folders recognise
// as ours) that is renamed over `path`, so a reader sees the old file or the new one, never half of
// one. Durability::synced also fsyncs the file before the rename and the folder after it, so the
// new file survives a power cut (the campaign store needs that; a run folder or a CSV a command
// writes once does not, and skips the cost).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "io/temp_files.hpp"  // unique_tmp_suffix, TempGuard: the temporaries' names and cleanup

namespace asperity::io {

enum class Durability { unsynced, synced };

// Throws std::runtime_error naming the path and the system's reason; the temporary is removed.
void write_file_atomically(const std::filesystem::path& path, const std::string& text, Durability durability);

// The same for a file too large to hold in memory: written piece by piece (buffered) into the
// temporary sibling, published by commit(); destroyed uncommitted, the temporary is removed and
// `path` is left as it was.
class AtomicFileWriter {
 public:
  AtomicFileWriter(const std::filesystem::path& path, Durability durability);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  void write(std::string_view bytes);
  void commit();

 private:
  void flush();
  void put(std::string_view bytes);
  std::filesystem::path path_, tmp_;
  std::optional<TempGuard> guard_;  // removes tmp_ if a signal stops the process
  Durability durability_;
  int fd_ = -1;
  std::string buffer_;
};

// Temp sibling, fsync, rename, fsync of the folder (the campaign store's files).
inline void write_file_durably(const std::filesystem::path& path, const std::string& text) {
  write_file_atomically(path, text, Durability::synced);
}

// Removes `path` (absent: nothing to do) and fsyncs its folder, so the removal survives a power
// cut (std::runtime_error naming the path otherwise).
void remove_file_durably(const std::filesystem::path& path);

// Writes all of `bytes` to the open descriptor `fd` (retrying short writes and EINTR); false with
// errno set on failure. For the store's append-only journal.
bool write_fully(int fd, std::string_view bytes);

// Reads a whole file (std::runtime_error when it cannot).
std::string read_file_text(const std::filesystem::path& path);

// Temp sibling + rename, no fsync (CSVs, YAML and reports a command writes once).
inline void write_text_file(const std::filesystem::path& path, const std::string& text) {
  write_file_atomically(path, text, Durability::unsynced);
}

}  // namespace asperity::io
