#pragma once
// Files and temporary folders for tests (no asperity header: usable by the tests of every layer).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace asperity::testing {
// The whole text of a file (empty when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Writes `text` to `p` byte for byte, making its parent folders; returns `p`.
inline std::filesystem::path write_text(const std::filesystem::path& p, const std::string& text) {
  if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// A path in the temporary folder unique to this process (test suites may run side by side).
inline std::filesystem::path temp_path(const std::string& stem, const std::string& ext = "") {
  std::string name = stem;
  name += '-';
  name += std::to_string(::getpid());
  name += ext;
  return std::filesystem::temp_directory_path() / name;
}

// The path in single quotes, for a command line the tests build (their paths hold no quote).
inline std::string shell_quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// An empty folder temp_path(stem) (removed first if a crashed run left it).
inline std::filesystem::path fresh_dir(const std::string& stem) {
  const std::filesystem::path d = temp_path(stem);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

// A fresh folder per call: fresh_dir(stem_N), N counting the calls in this process.
inline std::filesystem::path numbered_dir(const std::string& stem) {
  static int calls = 0;
  return fresh_dir(stem + "_" + std::to_string(calls++));
}

#ifdef ASPERITY_SOURCE_DIR
// The small campaigns and scenes the store, sweep and heat-map tests share.
inline const std::filesystem::path kCampaignData =
    std::filesystem::path(ASPERITY_SOURCE_DIR) / "tests" / "data" / "campaign";
#endif

// The lines of a text, without their line ends.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// FNV-1a 64 written out from its definition (offset basis and prime), independent of io/hash.
inline std::string fnv1a64_hex(const std::string& bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : bytes) h = (h ^ c) * 1099511628211ull;
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}
}  // namespace asperity::testing
