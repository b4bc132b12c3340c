#pragma once
// Temporary files and folders ("." NAME ".tmp-" HOST "-" PID "-" N, beside what they become):
// removed when the process is stopped by a signal while writing them, and found and removed by
// the next start when a process died without that chance (kill -9, a power cut, a node lost).
//
// The one piece of process-wide state: the registry of live temporaries a signal handler reads
// (a fixed array of slots, so the handler allocates nothing and takes no lock).
#include <filesystem>
#include <string>
#include <string_view>

namespace asperity::io {

// "HOST-PID-N": unique on the machine while the process lives, and telling which machine and
// process made a temporary (a cluster's nodes share folders).
std::string unique_tmp_suffix();

// ".NAME." (what every temporary of NAME starts with): NAME itself when NAME's temporaries fit in
// a file name's 255 bytes (NAME_MAX), else NAME's first bytes and a hash of all of it, so that a
// legal name of 250 bytes still has temporaries (the same NAME always gets the same prefix).
std::string temp_prefix(std::string_view name);

// temp_prefix(name) + "tmp-" + unique_tmp_suffix(): a temporary sibling of the file or folder
// NAME, within NAME_MAX whatever NAME's length.
std::string temp_name(std::string_view name);

// Registers `path` (a file or a folder) for removal if SIGINT, SIGTERM or SIGHUP stops the
// process while the guard lives (install_signal_cleanup() must have been called).
class TempGuard {
 public:
  explicit TempGuard(const std::filesystem::path& path);
  ~TempGuard();
  TempGuard(const TempGuard&) = delete;
  TempGuard& operator=(const TempGuard&) = delete;

 private:
  int slot_ = -1;  // -1: every slot taken (the next start removes it instead)
};

// For the command line (not a library embedded in Python, whose interpreter owns the signals):
// SIGINT, SIGTERM and SIGHUP remove the registered temporaries and then end the process as the
// signal would (exit status 128 + signal to the shell; SLURM's preemption sends SIGTERM);
// SIGXFSZ is ignored, so a write past the file-size limit fails with EFBIG and the writer's own
// cleanup runs. A handler installed later for SIGINT (run's Ctrl-C flag) takes precedence while
// it is installed.
void install_signal_cleanup();

// Removes the temporaries among the entries of `folder` whose names start with `prefix` and
// carry ".tmp-" or ".old-" + suffix, when their process is gone: made on this host by a PID
// that no longer exists, or (any host) last modified more than a day ago. Returns how many.
// Names without a host ("PID-N", written before hosts were recorded) count as this host's.
std::size_t remove_stale_temporaries(const std::filesystem::path& folder, std::string_view prefix = ".");

}  // namespace asperity::io
