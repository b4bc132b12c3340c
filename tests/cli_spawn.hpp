#pragma once
// Runs the asperity binary with an argument vector, without a shell: hostile paths and values
// reach it exactly as written. Output goes to files outside the working folder, so that a
// snapshot of that folder sees only what the command wrote.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "support_files.hpp"

extern char** environ;

namespace asperity::testing {

struct CliResult {
  int status = -1;  // exit status (-1: did not exit normally)
  std::string out, err;
};

inline CliResult run_argv(const std::filesystem::path& work, const std::vector<std::string>& args) {
  const std::filesystem::path out = temp_path("asperity-cli-stdout"), err = temp_path("asperity-cli-stderr");
  std::vector<std::string> all{ASPERITY_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addchdir_np(&fa, work.c_str());
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  CliResult r;
  if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ) == 0) {
    int st = 0;
    while (waitpid(pid, &st, 0) < 0) {
    }
    r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  }
  posix_spawn_file_actions_destroy(&fa);
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// Every file and folder under `dir` (relative path → bytes; folders map to "<dir>").
inline std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  std::map<std::string, std::string> s;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string rel = std::filesystem::relative(e.path(), dir).string();
    s[rel] = e.is_directory() ? std::string("<dir>") : slurp(e.path());
  }
  return s;
}

}  // namespace asperity::testing
