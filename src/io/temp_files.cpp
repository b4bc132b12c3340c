#include "io/temp_files.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>

#include "io/hash.hpp"

namespace asperity::io {
namespace fs = std::filesystem;
namespace {

constexpr int kSlots = 64;
// The longest "HOST-PID-N": a host of 64 bytes, a PID and a counter of 10 digits each.
constexpr std::size_t kHostMax = 64;
constexpr std::size_t kSuffixMax = kHostMax + 1 + 10 + 1 + 10;
constexpr std::size_t kNameMax = 255;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live
  char path[4096];
};
Slot g_slots[kSlots];  // read by the signal handler (see the header)

std::string host_name() {
  char h[256] = {};
  if (::gethostname(h, sizeof h - 1) != 0 || !h[0]) return "host";
  std::string s(h);
  s.resize(std::min<std::size_t>(s.size(), kHostMax));  // bounds the temporaries' names (temp_prefix)
  for (char& c : s)
    if (c == '/' || c == '-' || static_cast<unsigned char>(c) < 0x21) c = '_';  // '-' separates fields
  return s;
}

const std::string& this_host() {
  static const std::string h = host_name();
  return h;
}

// Async-signal-safe removal of a file or a folder tree (system calls only: no allocation).
void remove_children(int dfd, int depth);
void remove_entry(int dfd, const char* name, bool dir, int depth) {
  if (!dir && ::unlinkat(dfd, name, 0) == 0) return;
  const int cfd = ::openat(dfd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (cfd < 0) {
    ::unlinkat(dfd, name, 0);
    return;
  }
  remove_children(cfd, depth + 1);
  ::close(cfd);
  ::unlinkat(dfd, name, AT_REMOVEDIR);
}
void remove_children(int dfd, int depth) {
  if (depth > 16) return;  // our temporaries are a few levels deep
  alignas(8) char buf[4096];
  for (int pass = 0; pass < 64; ++pass) {  // entries removed while listing: list again until empty
    ::lseek(dfd, 0, SEEK_SET);
    bool removed = false;
    for (;;) {
      const long n = ::syscall(SYS_getdents64, dfd, buf, sizeof buf);
      if (n <= 0) break;
      for (long at = 0; at < n;) {
        struct Entry {
          unsigned long long ino;
          long long off;
          unsigned short reclen;
          unsigned char type;
          char name[1];
        };
        const auto* e = reinterpret_cast<const Entry*>(buf + at);
        at += e->reclen;
        if (e->name[0] == '.' && (e->name[1] == 0 || (e->name[1] == '.' && e->name[2] == 0))) continue;
        remove_entry(dfd, e->name, e->type == DT_DIR, depth);
        removed = true;
      }
    }
    if (!removed) return;
  }
}
void remove_tree(const char* path) {
  if (::unlink(path) == 0 || errno == ENOENT) return;
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  remove_children(fd, 0);
  ::close(fd);
  ::rmdir(path);
}

extern "C" void on_stop_signal(int sig) {
  const int saved = errno;
  for (Slot& s : g_slots)
    if (s.state.load(std::memory_order_acquire) == 2) remove_tree(s.path);
  errno = saved;
  // SA_RESETHAND restored the default action: the signal, blocked while we run, ends the process
  // as soon as this handler returns.
  ::raise(sig);
}

}  // namespace

std::string unique_tmp_suffix() {
  static std::atomic<unsigned> counter{0};  // several threads may write files of one folder
  return this_host() + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

std::string temp_prefix(std::string_view name) {
  // "." NAME "." "tmp-" SUFFIX must fit in kNameMax.
  constexpr std::size_t kFits = kNameMax - 2 - 4 - kSuffixMax;
  constexpr std::size_t kKept = kFits - 1 - 16;  // the first bytes, "~" and 16 hex digits
  std::string p = ".";
  if (name.size() <= kFits) {
    p.append(name);
  } else {
    std::size_t keep = kKept;
    while (keep > 0 && (static_cast<unsigned char>(name[keep]) & 0xC0) == 0x80) --keep;  // whole UTF-8 characters
    p.append(name.substr(0, keep)).append("~").append(hex16(fnv1a64(name)));
  }
  return p.append(".");
}

std::string temp_name(std::string_view name) { return temp_prefix(name) + "tmp-" + unique_tmp_suffix(); }

TempGuard::TempGuard(const fs::path& path) {
  const std::string p = fs::absolute(path).string();
  if (p.size() >= sizeof(Slot::path)) return;
  for (int i = 0; i < kSlots; ++i) {
    int free = 0;
    if (g_slots[i].state.compare_exchange_strong(free, 1, std::memory_order_acq_rel)) {
      std::memcpy(g_slots[i].path, p.c_str(), p.size() + 1);
      g_slots[i].state.store(2, std::memory_order_release);
      slot_ = i;
      return;
    }
  }
}

TempGuard::~TempGuard() {
  if (slot_ >= 0) g_slots[slot_].state.store(0, std::memory_order_release);
}

void install_signal_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sa.sa_flags = SA_RESETHAND;
  sigemptyset(&sa.sa_mask);
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(sig, &sa, nullptr);
  std::signal(SIGXFSZ, SIG_IGN);
}

std::size_t remove_stale_temporaries(const fs::path& folder, std::string_view prefix) {
  std::size_t removed = 0;
  std::error_code ec;
  fs::directory_iterator it(folder, ec), end;
  if (ec) return 0;
  const auto day_ago = fs::file_time_type::clock::now() - std::chrono::hours(24);
  for (; it != end; it.increment(ec)) {
    if (ec) break;
    const std::string name = it->path().filename().string();
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    std::size_t at = name.rfind(".tmp-");
    if (at == std::string::npos) at = name.rfind(".old-");
    if (at == std::string::npos) continue;
    // HOST-PID-N (or PID-N): the last two fields are PID and N.
    const std::string tail = name.substr(at + 5);
    const std::size_t n_dash = tail.rfind('-');
    if (n_dash == std::string::npos || n_dash == 0) continue;
    const std::size_t pid_dash = tail.rfind('-', n_dash - 1);
    const std::string pid_text =
        pid_dash == std::string::npos ? tail.substr(0, n_dash) : tail.substr(pid_dash + 1, n_dash - pid_dash - 1);
    const std::string host = pid_dash == std::string::npos ? this_host() : tail.substr(0, pid_dash);
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos || pid_text.size() > 9)
      continue;
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    bool stale = host == this_host() && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH;
    if (!stale) {
      const auto t = it->last_write_time(ec);
      stale = !ec && t < day_ago;
    }
    if (stale) {
      remove_tree(it->path().c_str());
      ++removed;
    }
  }
  return removed;
}

}  // namespace asperity::io
