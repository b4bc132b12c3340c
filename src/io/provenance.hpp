#pragma once
// Where a result came from, written into every result (summary.yaml, a store's provenance.yaml,
// fit.yaml): the build (version, git commit, compiler, the libraries it was built against), the
// command line, and the content hash of each data file, so a result can be traced and a stale
// one recognised after its data changed.
#include <filesystem>
#include <string>
#include <vector>

namespace asperity::io {

struct BuildInfo {
  std::string version;     // project version, e.g. "0.1.0"
  std::string git_commit;  // 12 hex digits (+ "-dirty"), "unknown" outside a checkout
  std::string build_type;  // CMake build type
  std::string compiler;    // e.g. "GCC 12.2.0"
  std::string libraries;   // versions found at configure time, e.g. "Boost 1.74.0, Eigen 3.4.0, ..."
};

// The build this binary is (constants fixed at compile time).
BuildInfo build_info();

// The build a resumed result may trust to have computed what it stored: "asperity VERSION commit
// COMMIT BUILD_TYPE COMPILER", or "" when the commit is unknown or "-dirty" (such a binary's code
// may differ from its commit's, so it names no code).
std::string clean_build_id();

// The code of this executable for a fit journal, which must never mix evaluations of two codes:
// clean_build_id(), or for an unknown or "-dirty" commit the same text plus the FNV-1a 64 of the
// executable's bytes (/proc/self/exe; "" when unreadable): a developer's rebuilt binary is
// another code, the same binary resumes its own journal.
std::string code_build_id();

// "asperity 0.1.0 (commit 612a57f3c2ab, Release, GCC 12.2.0)": what --version prints.
std::string version_line();

// A file as a result names it: relative to the working directory when inside it (a committed
// result names no machine path), else as given. (Messages name a file otherwise: input_path of
// io/input_error.hpp.)
std::string result_path(const std::filesystem::path& file);

// One input file of a result and the FNV-1a 64 hash of its bytes.
struct DataFile {
  std::string role;  // "scene", "experiment", "junctions", "measured", "campaign", "fit"
  std::filesystem::path path;
};

// The `provenance:` block (YAML, two-space indent, ends with a newline): the build, the command
// line and each file's content hash (a file that cannot be read is listed with hash "unreadable").
// Files listed twice (same path) appear once.
std::string provenance_yaml(const std::string& command_line, const std::vector<DataFile>& files);

}  // namespace asperity::io
