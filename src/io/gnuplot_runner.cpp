#include "io/gnuplot_runner.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>

extern char** environ;

namespace asperity::io {
namespace fs = std::filesystem;

namespace {

// gnuplot's full path from $PATH (empty when absent): spawned directly, never through a shell.
fs::path find_gnuplot() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  for (std::size_t pos = 0; pos <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', pos), dirs.size());
    const fs::path dir = dirs.substr(pos, end - pos);
    const fs::path exe = (dir.empty() ? fs::path(".") : dir) / "gnuplot";
    std::error_code ec;
    if (fs::is_regular_file(exe, ec) && ::access(exe.c_str(), X_OK) == 0) return exe;
    pos = end + 1;
  }
  return {};
}

// Closes a file descriptor when it goes out of scope.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
  void reset() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

}  // namespace

bool gnuplot_available() { return !find_gnuplot().empty(); }

void run_gnuplot(const fs::path& workdir, const std::string& script) {
  const fs::path exe = find_gnuplot();
  if (exe.empty())
    throw std::runtime_error("gnuplot not found: install it (apt-get install gnuplot-nox) to draw plots");
  // The script goes through a socket (send with MSG_NOSIGNAL: a gnuplot that dies early gives
  // EPIPE, not a SIGPIPE that would kill us); its messages go to an anonymous memory file.
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
    throw std::runtime_error(std::string("cannot start gnuplot: ") + std::strerror(errno));
  Fd ours{sv[0]}, theirs{sv[1]};
  Fd err{::memfd_create("gnuplot-stderr", MFD_CLOEXEC)};
  if (err.fd < 0) throw std::runtime_error(std::string("cannot start gnuplot: ") + std::strerror(errno));

  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_adddup2(&fa, theirs.fd, 0);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, err.fd, 2);
  posix_spawn_file_actions_addchdir_np(&fa, workdir.empty() ? "." : workdir.c_str());
  char arg0[] = "gnuplot";
  char* argv[] = {arg0, nullptr};
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  if (spawned != 0) throw std::runtime_error("cannot start gnuplot: " + std::string(std::strerror(spawned)));
  theirs.reset();

  std::size_t sent = 0;
  while (sent < script.size()) {
    const ssize_t n = ::send(ours.fd, script.data() + sent, script.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // gnuplot stopped reading (an error): its status says why
    sent += static_cast<std::size_t>(n);
  }
  ours.reset();  // end of input: gnuplot exits
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;

  // The first non-blank line of gnuplot's messages that names the problem.
  std::string msg(4096, '\0');
  const ssize_t got = ::pread(err.fd, msg.data(), msg.size(), 0);
  msg.resize(got > 0 ? static_cast<std::size_t>(got) : 0);
  std::string first;
  for (std::size_t pos = 0; pos < msg.size();) {
    const std::size_t nl = std::min(msg.find('\n', pos), msg.size());
    const std::string line = msg.substr(pos, nl - pos);
    pos = nl + 1;
    if (line.find("line ") != std::string::npos || line.find("rror") != std::string::npos) {
      first = line;
      break;
    }
    if (first.empty() && line.find_first_not_of(" \t^") != std::string::npos) first = line;
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  throw std::runtime_error("gnuplot failed (status " + std::to_string(code) + "): " + first);
}

}  // namespace asperity::io
