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

namespace asperity {
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

std::string unique_tmp_suffix() {
  static std::atomic<unsigned> counter{0};  // several threads may write files of one folder
  return std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void write_file_atomically(const fs::path& path, const std::string& text, Durability durability) {
  std::string name = ".";  // (built by append: GCC 12 warns falsely on "." + std::string)
  name.append(path.filename().string()).append(".tmp-").append(unique_tmp_suffix());
  const fs::path tmp = path.parent_path() / name;
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) sys_fail("cannot create", tmp, errno);
  const bool synced = durability == Durability::synced;
  bool ok = write_fully(fd, text) && (!synced || ::fsync(fd) == 0);
  int err = errno;
  if (::close(fd) != 0 && ok) ok = false, err = errno;
  if (!ok) {
    std::error_code ec;
    fs::remove(tmp, ec);
    sys_fail("cannot write", tmp, err);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    err = errno;
    std::error_code ec;
    fs::remove(tmp, ec);
    sys_fail("cannot rename into", path, err);
  }
  if (synced) fsync_dir(path.parent_path().empty() ? fs::path(".") : path.parent_path());
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

}  // namespace asperity
