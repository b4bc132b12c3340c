#include "batch/journal_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/journal_line.hpp"
#include "io/safe_open.hpp"

namespace asperity {

namespace {

[[noreturn]] void sys_fail(const std::string& what, const std::string& name) {
  throw std::runtime_error(what + " " + name + ": " + std::strerror(errno));
}

}  // namespace

JournalFile::JournalFile(const std::filesystem::path& path, bool readable, std::string name) : name_(std::move(name)) {
  fd_ = io::open_regular(path, (readable ? O_RDWR : O_WRONLY) | O_APPEND, "--out");
  if (fd_ < 0) sys_fail("cannot open", path.string());
}

JournalFile::~JournalFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t JournalFile::append(std::string_view row) {
  const std::string line = io::journal_line(row);
  if (!io::write_fully(fd_, line)) sys_fail("cannot write", name_);
  return line.size();
}

void JournalFile::append_durably(std::string_view row) {
  if (!io::write_fully(fd_, io::journal_line(row)) || ::fdatasync(fd_) != 0) sys_fail("cannot write", name_);
}

void JournalFile::sync() {
  if (::fdatasync(fd_) != 0) sys_fail("cannot sync", name_);
}

bool JournalFile::try_sync() noexcept { return ::fdatasync(fd_) == 0; }

void JournalFile::cut(std::uint64_t size) {
  // Only what follows the last good line is cut, so nothing computed is lost; the sync makes the
  // cut survive a power cut too.
  if (::ftruncate(fd_, static_cast<off_t>(size)) != 0) sys_fail("cannot cut the torn tail of", name_);
  sync();
}

std::string read_line_at(int fd, std::uint64_t offset, const std::string& name) {
  std::string s;
  char buf[1024];
  for (;;) {
    const ssize_t r = ::pread(fd, buf, sizeof buf, static_cast<off_t>(offset + s.size()));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) throw std::runtime_error("cannot read " + name + " (a row ends without its newline)");
    const char* nl = static_cast<const char*>(std::memchr(buf, '\n', static_cast<std::size_t>(r)));
    s.append(buf, nl ? static_cast<std::size_t>(nl - buf) : static_cast<std::size_t>(r));
    if (nl) return s;
  }
}

}  // namespace asperity
