#include "io/dir_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "io/safe_open.hpp"

namespace asperity::io {

DirLock::DirLock(const std::filesystem::path& dir, const std::string& who) {
  const std::filesystem::path p = dir / ".lock";
  fd_ = open_regular(p, O_RDWR | O_CREAT, "--out");  // never through a link, never a FIFO
  if (fd_ < 0) throw std::runtime_error("cannot open " + p.string() + ": " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("another " + who + " is writing " + dir.string() + " (" + p.string() + " is locked)");
  }
}

DirLock::~DirLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace asperity::io
