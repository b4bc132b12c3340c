#pragma once
// An exclusive lock on DIR/.lock (flock, non-blocking) held for the object's lifetime: one writer
// per folder (a sweep store, a fit's journal). The kernel drops it when the process dies, so a
// killed run never leaves a stale lock behind.
#include <filesystem>
#include <string>

namespace asperity::io {

class DirLock {
 public:
  // std::runtime_error "another WHO is writing DIR (DIR/.lock is locked)" when another process
  // holds it (`who`: "sweep", "fit", ...).
  DirLock(const std::filesystem::path& dir, const std::string& who);
  ~DirLock();
  DirLock(const DirLock&) = delete;
  DirLock& operator=(const DirLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace asperity::io
