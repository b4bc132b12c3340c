#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace asperity::io {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void sys_fail(const std::string& what, const fs::path& p, int err) {
  throw std::runtime_error(what + " " + p.string() + ": " + std::strerror(err));
}

void fsync_dir(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

}  // namespace

bool write_fully(int fd, std::string_view bytes) {
  const char* data = bytes.data();
  std::size_t n = bytes.size();
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
  return true;
}

AtomicFileWriter::AtomicFileWriter(const fs::path& path, Durability durability) : path_(path), durability_(durability) {
  tmp_ = path.parent_path() / temp_name(path.filename().string());
  // Guarded before it exists: a signal between its creation and the guard would leave it behind.
  guard_.emplace(tmp_);
  // O_EXCL | O_NOFOLLOW: a name planted in advance (a link to elsewhere) is never written through.
  fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0) sys_fail("cannot create", tmp_, errno);
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ < 0) return;
  ::close(fd_);
  std::error_code ec;
  fs::remove(tmp_, ec);
}

void AtomicFileWriter::flush() { put(buffer_), buffer_.clear(); }

void AtomicFileWriter::put(std::string_view bytes) {
  if (write_fully(fd_, bytes)) return;
  const int err = errno;
  ::close(fd_);
  fd_ = -1;
  std::error_code ec;
  fs::remove(tmp_, ec);
  sys_fail("cannot write", tmp_, err);
}

void AtomicFileWriter::write(std::string_view bytes) {
  constexpr std::size_t kBuffer = 1u << 20;
  if (fd_ < 0) throw std::logic_error("AtomicFileWriter: write after commit");
  if (buffer_.size() + bytes.size() < kBuffer) {
    buffer_.append(bytes);
    return;
  }
  flush();
  if (bytes.size() >= kBuffer)
    put(bytes);  // large pieces go straight to the file, uncopied
  else
    buffer_.append(bytes);
}

void AtomicFileWriter::commit() {
  flush();
  const bool synced = durability_ == Durability::synced;
  bool ok = !synced || ::fsync(fd_) == 0;
  int err = errno;
  if (::close(fd_) != 0 && ok) ok = false, err = errno;
  fd_ = -1;
  if (!ok) {
    std::error_code ec;
    fs::remove(tmp_, ec);
    sys_fail("cannot write", tmp_, err);
  }
  if (::rename(tmp_.c_str(), path_.c_str()) != 0) {
    err = errno;
    std::error_code ec;
    fs::remove(tmp_, ec);
    sys_fail("cannot rename into", path_, err);
  }
  guard_.reset();
  if (synced) fsync_dir(path_.parent_path().empty() ? fs::path(".") : path_.parent_path());
}

void write_file_atomically(const fs::path& path, const std::string& text, Durability durability) {
  AtomicFileWriter w(path, durability);
  w.write(text);
  w.commit();
}

void remove_file_durably(const fs::path& path) {
  if (::unlink(path.c_str()) != 0) {
    if (errno == ENOENT) return;
    sys_fail("cannot remove", path, errno);
  }
  fsync_dir(path.parent_path().empty() ? fs::path(".") : path.parent_path());
}

std::string read_file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace asperity::io
