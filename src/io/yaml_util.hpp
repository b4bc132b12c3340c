#pragma once
// Internal to src/scene: typed, located reading of yaml-cpp trees. Every failure is an
// InputError naming the file, the line (from the node's Mark) and the dotted key.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/input_error.hpp"
#include "io/numbers.hpp"

namespace asperity::io {

// A command-line override as applied to a scene tree.
struct SetRecord {
  std::string key;   // dotted key, e.g. model.eta
  std::string text;  // "--set model.eta=abc" (what an error names instead of FILE:LINE)
};

// Where the nodes of a tree come from. Nodes with a Mark come from `file`; nodes without one
// were put there by an override (apply_override strips marks), and an error on them names the
// matching --set when known, else `file` without a line.
struct Source {
  std::string file;                              // display path
  const std::vector<SetRecord>* sets = nullptr;  // overrides applied to this tree, in order
  // Every dotted key of this kind of file ("solver.tolerance", ...), when known: an unknown key
  // that is valid at another depth is named with where it belongs (an indentation slip).
  const std::vector<std::string>* layout = nullptr;
};

// " ('tolerance' is solver.tolerance: check its indentation)" when `key` at `path` is the last
// part of a dotted key of `layout` that sits elsewhere, or a section of it; else "".
std::string misplaced_key_hint(const std::string& path, const std::string& key, const std::vector<std::string>& layout);

// Where the value at `at` came from, as a message names it: {file, line}, or {"--set k=v", 0}
// for a node an override put there, or {file, fallback_line}.
std::pair<std::string, int> value_origin(const Source& src, const YAML::Node& at, const std::string& key,
                                         int fallback_line = 0);
[[noreturn]] void fail(const Source& src, const YAML::Node& at, const std::string& key, const std::string& message,
                       int fallback_line = 0);

std::string join_key(const std::string& path, const std::string& key);
std::string node_kind(const YAML::Node& n);                             // "a map", "a list", "a value", "nothing"
std::size_t edit_distance(const std::string& a, const std::string& b);  // case-insensitive
// " (did you mean 'x'?)" when some candidate is within edit distance 2, else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates);
std::string join(const std::vector<std::string>& v, const char* sep = ", ");

// Size caps of input files, far above any real one, so that a wrong path (a disk image, a log)
// fails at once instead of filling memory. YAML: hand-written scenes, experiments, campaigns
// and fits are kilobytes; yaml-cpp needs ~100 bytes of memory per byte of text, so 16 MiB is
// the most that loads in a couple of GB. CSV: the 10^6-junction population is 23 MB; 256 MiB
// (~10^7 junctions) still loads in ~2 GB and runs in ~2 GB more.
inline constexpr std::uintmax_t kMaxYamlBytes = std::uintmax_t{16} << 20;
inline constexpr std::uintmax_t kMaxCsvBytes = std::uintmax_t{256} << 20;
// A YAML text with its aliases expanded may hold at most this many nodes plus scalar characters
// (or 4 × its own size, if larger): enough for any scene or campaign written out by hand, far
// below the gigabytes of nested aliases (a "billion laughs").
inline constexpr std::uint64_t kMaxYamlExpansion = 1'000'000;

// Why `path` cannot be an input file: "" when it is a regular file (after symlinks) of at most
// max_bytes, else e.g. "file not found", "is a directory, not a file", "is a character device, not a
// regular file", "is 17 GB, more than the 16 MiB an input file may have".
std::string input_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes);

// The whole text of an input file; any problem above (checked on the opened file, so a file
// swapped after the check is caught too) or a read error → InputError "display: message".
// Never blocks on a FIFO and never reads more than max_bytes + 1 bytes.
std::string read_input_file(const std::filesystem::path& path, const std::string& display, std::uintmax_t max_bytes);

// Reads a whole YAML file (first and only document, read_input_file with kMaxYamlBytes); Null
// when empty. Parse errors → InputError.
YAML::Node load_yaml_file(const std::filesystem::path& path, const std::string& display);
// Parses a whole YAML document given as text, as load_yaml_file parses a file's (lines kept for
// messages, which name `display`).
YAML::Node load_yaml_document(const std::string& text, const std::string& display);
// Parses YAML text (an override value); errors are reported against `where`.
YAML::Node load_yaml_text(const std::string& text, const std::string& where, const std::string& key);

// Deep copy without Marks (values coming from outside the file being read).
YAML::Node strip_marks(const YAML::Node& n);

// A map node with its keys checked: a map (or empty), scalar keys, no duplicates, no unknown keys.
class MapView {
 public:
  MapView(Source src, const YAML::Node& node, std::string path, std::vector<std::string> allowed,
          int fallback_line = 0);

  const Source& source() const { return src_; }
  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  std::string key(const std::string& k) const { return join_key(path_, k); }
  std::optional<YAML::Node> find(const std::string& k) const;
  YAML::Node require(const std::string& k) const;  // missing → InputError
  [[noreturn]] void fail_at(const YAML::Node& at, const std::string& k, const std::string& msg) const;
  // A warning (io/warnings.hpp) "FILE:LINE: msg" (or "--set k=v: msg") about the value at `at`.
  void warn_at(const YAML::Node& at, const std::string& k, const std::string& msg) const;

  // Typed values. `unit` names the SI unit for the "1.6 MPa" message (nullptr: dimensionless).
  double number(const YAML::Node& n, const std::string& k, const char* unit) const;
  int integer(const YAML::Node& n, const std::string& k) const;
  // A random seed: a non-negative integer below 2^64, written out in full.
  std::uint64_t seed(const YAML::Node& n, const std::string& k) const;
  bool boolean(const YAML::Node& n, const std::string& k) const;
  std::string string(const YAML::Node& n, const std::string& k) const;
  std::vector<std::string> string_list(const YAML::Node& n, const std::string& k) const;
  template <class E>
  E enumeration(const YAML::Node& n, const std::string& k,
                std::initializer_list<std::pair<const char*, E>> table) const {
    const std::string s = string(n, k);
    std::vector<std::string> names;
    for (const auto& [name, value] : table) {
      if (s == name) return value;
      names.emplace_back(name);
    }
    fail_at(n, k, "unknown value " + quote(s) + did_you_mean(s, names) + "; valid: " + join(names));
  }

 private:
  Source src_;
  YAML::Node node_;
  std::string path_;
  int fallback_line_;
  std::vector<std::pair<std::string, std::pair<YAML::Node, YAML::Node>>> entries_;  // key → (key node, value)
};

// A double-quoted YAML scalar with escapes (the one quoting used for every file we write;
// deterministic bytes).
std::string yaml_quoted(const std::string& s);

}  // namespace asperity::io
