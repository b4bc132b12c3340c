#pragma once
// The one exception every bad input becomes: a scene or experiment YAML, a junction or measured
// CSV, or a command-line override. what() is one line: "FILE:LINE: KEY: message" (YAML),
// "FILE:LINE:COL: COLUMN: message" (CSV), "--set k=v: KEY: message" (override).
#include <filesystem>
#include <stdexcept>
#include <string>

namespace asperity::io {

struct InputError : std::runtime_error {
  std::string file;     // path as the user gave it (lexically normalised), or "--set key=value"
  int line = 0;         // 1-based; 0 when unknown (or for command-line overrides)
  int column = 0;       // 1-based CSV column; 0 for YAML
  std::string key;      // dotted key (model.eta) or CSV column name; may be empty
  std::string message;  // the bare message, without location

  InputError(std::string file, int line, std::string key, std::string message, int column = 0);

  // "FILE:LINE:COL: KEY: message", leaving out the parts that are empty/0; one line.
  static std::string format(const std::string& file, int line, int column, const std::string& key,
                            const std::string& message);
};

// A file as InputError::file and the loaders' messages name it: as the user gave it, lexically
// normalised. (A result names a file otherwise: result_path of io/provenance.hpp.)
std::string input_path(const std::filesystem::path& file);

}  // namespace asperity::io
