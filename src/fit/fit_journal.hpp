#pragma once
// The evaluation journal of a fit (DIR/journal.csv, or DIR/tasks/I-of-N/journal.csv for one array
// task): every objective evaluation, appended as it finishes, so that a killed fit resumes without
// repeating one. Lines (io/journal_line.hpp: each ends with the SHA-256 of the row, appended
// with one write() and fdatasync'd at once: an evaluation costs a model run, tens of ms at least,
// so a flush per evaluation is cheap and a kill or a power cut loses only evaluations in flight):
//   part,optimization,evaluation,x,objective,terms,status,wall_s,sha256
//   fit,P0.98N,1,5.2e-16,0.0123,0.0123,ok,0.41,1f0c…          one evaluation of an optimization
//   profile,P0.98N,3,…                                         a profile point (evaluation = point)
//   refit experiment.E -1,P0.98N,2,…                           an error-bar refit's evaluation
// `x` and `terms` list the free variables' SI values and the experiments' terms, separated by ';',
// as shortest round-trip numbers: a value read back is the double that was evaluated, bit for bit.
//
// Replay: NLopt's derivative-free algorithms are deterministic, so a resumed fit asks for the
// same points in the same order; find() answers a point of a (part, optimization) whose exact
// values are journaled with the journaled evaluation instead of running the model again.
//
// Reading is strict (the file is input): a torn last line, or a tail of damaged lines after the
// last good one (a kill, a power cut before the flush), is dropped; a damaged line followed by
// good ones, a wrong header or a malformed field is InputError "FILE:LINE: KEY: message".
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "batch/journal_file.hpp"
#include "fit/fit.hpp"
#include "io/dir_lock.hpp"

namespace asperity {

class FitJournal {
 public:
  FitJournal() = default;
  ~FitJournal();
  FitJournal(const FitJournal&) = delete;
  FitJournal& operator=(const FitJournal&) = delete;

  // Reads `file` (when present) into the replay index. The first file opened with
  // `append` (created when absent, its torn tail cut off) receives append()s.
  void open(const std::filesystem::path& file, bool append);

  // The journaled evaluation of (part, optimization) at exactly `x` (thread-safe).
  std::optional<Evaluation> find(const std::string& part, const std::string& optimization,
                                 const std::vector<double>& x) const;
  // The file and line that hold that evaluation; nothing when it was not read from a file
  // (computed by this process, or absent).
  std::optional<std::pair<std::string, int>> where(const std::string& part, const std::string& optimization,
                                                   const std::vector<double>& x) const;
  // Appends one evaluation and makes it durable (thread-safe; std::runtime_error on I/O failure).
  void append(const std::string& part, const std::string& optimization, const Evaluation& ev);

  std::size_t size() const;                               // evaluations indexed
  std::size_t dropped_lines() const { return dropped_; }  // torn or damaged tail lines dropped
  const std::vector<std::filesystem::path>& files() const { return files_; }

 private:
  void read(const std::filesystem::path& file, bool append);
  mutable std::mutex mutex_;
  std::map<std::string, Evaluation> index_;                   // part '\n' optimization '\n' x text → evaluation
  std::map<std::string, std::pair<std::string, int>> where_;  // the same key → file, line it was read from
  std::vector<std::filesystem::path> files_;
  std::unique_ptr<JournalFile> file_;  // the one file append()s go to
  std::size_t dropped_ = 0;
};

// The text a journal line holds for these values (';'-separated shortest round-trip numbers).
std::string journal_values(const std::vector<double>& x);

// One writer per journal folder (DirLock "asperity fit"); another process holding it → InputError
// naming `dir`, key `option` ("--out" on the command line, "out" in Python).
std::unique_ptr<io::DirLock> lock_fit_journal_dir(const std::filesystem::path& dir, const std::string& option);

// Opens DIR/journal.csv for appending after checking DIR/inputs.txt says it was computed from
// `inputs` (fit_inputs.hpp; InputError otherwise). A new journal: inputs.txt is written first,
// durably, so a journal never exists without it.
void open_fit_journal(FitJournal& journal, const std::filesystem::path& dir, const std::string& inputs);

}  // namespace asperity
