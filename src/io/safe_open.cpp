#include "io/safe_open.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "io/input_error.hpp"

namespace asperity::io {
namespace fs = std::filesystem;
namespace {

struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
  int release() {
    const int f = fd;
    fd = -1;
    return f;
  }
};

const char* what_it_is(mode_t m) {
  if (S_ISLNK(m)) return "a symbolic link";
  if (S_ISFIFO(m)) return "a FIFO";
  if (S_ISCHR(m) || S_ISBLK(m)) return "a device";
  if (S_ISSOCK(m)) return "a socket";
  if (S_ISDIR(m)) return "a folder";
  return "not a regular file";
}

[[noreturn]] void refuse(const fs::path& p, const std::string& key, const std::string& what) {
  throw InputError(p.string(), 0, key,
                   "is " + what +
                       ": asperity reads and writes only regular files inside its output folders "
                       "(never through a link, never a FIFO or device); remove it");
}

[[noreturn]] void fail(const std::string& what, const fs::path& p) {
  throw std::runtime_error(what + " " + p.string() + ": " + std::strerror(errno));
}

// Opens each folder of `rel` but the last component from `dirfd`, without following links;
// returns the descriptor of the last folder (or -1, errno ENOENT, when one is absent).
int walk(int dirfd, const fs::path& folder, const fs::path& rel, const std::string& key, fs::path& at) {
  Fd cur{::dup(dirfd)};
  if (cur.fd < 0) fail("cannot open", folder);
  at = folder;
  const fs::path parent = rel.parent_path();
  for (const fs::path& part : parent) {
    if (part.empty() || part == ".") continue;
    at /= part;
    Fd next{::openat(cur.fd, part.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC)};
    if (next.fd < 0) {
      if (errno == ENOENT) return -1;
      struct stat st {};
      if (::fstatat(cur.fd, part.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) refuse(at, key, what_it_is(st.st_mode));
      fail("cannot open", at);
    }
    std::swap(cur.fd, next.fd);
  }
  return cur.release();
}

}  // namespace

int open_in_folder(const fs::path& folder, const fs::path& rel, int flags, const std::string& key, mode_t mode) {
  if (rel.empty() || rel.is_absolute()) throw std::logic_error("open_in_folder: a relative path is needed");
  Fd root{::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)};
  if (root.fd < 0) {
    if (errno == ENOENT && !(flags & O_CREAT)) return -1;
    fail("cannot open", folder);
  }
  fs::path at;
  Fd dir{walk(root.fd, folder, rel, key, at)};
  if (dir.fd < 0) {
    if (!(flags & O_CREAT)) return errno = ENOENT, -1;
    fail("cannot open", at);
  }
  const fs::path file = folder / rel;
  const std::string name = rel.filename().string();
  Fd f{::openat(dir.fd, name.c_str(), flags | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, mode)};
  if (f.fd < 0) {
    const int err = errno;
    if (err == ENOENT) return -1;
    struct stat st {};
    if (::fstatat(dir.fd, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
      refuse(file, key, what_it_is(st.st_mode));
    errno = err;
    fail("cannot open", file);
  }
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) fail("cannot stat", file);
  if (!S_ISREG(st.st_mode)) refuse(file, key, what_it_is(st.st_mode));
  // Blocking I/O from here on (O_NONBLOCK only kept a FIFO from blocking the open).
  const int fl = ::fcntl(f.fd, F_GETFL);
  if (fl < 0 || ::fcntl(f.fd, F_SETFL, fl & ~O_NONBLOCK) != 0) fail("cannot set flags of", file);
  return f.release();
}

int open_regular(const fs::path& path, int flags, const std::string& key, mode_t mode) {
  const fs::path folder = path.has_parent_path() ? path.parent_path() : fs::path(".");
  return open_in_folder(folder, path.filename(), flags, key, mode);
}

void check_real_folders(const fs::path& folder, const fs::path& rel, const std::string& key) {
  fs::path at = folder;
  for (const fs::path& part : rel) {
    if (part.empty() || part == ".") continue;
    at /= part;
    struct stat st {};
    if (::lstat(at.c_str(), &st) != 0) return;  // absent from here on
    if (!S_ISDIR(st.st_mode)) refuse(at, key, what_it_is(st.st_mode));
  }
}

bool read_regular(const fs::path& path, std::string& text, const std::string& key) {
  Fd f{open_regular(path, O_RDONLY, key)};
  if (f.fd < 0) return false;
  text.clear();
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("cannot read", path);
    }
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
  }
  return true;
}

}  // namespace asperity::io
