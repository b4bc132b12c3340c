#pragma once
// DIR/inputs.txt beside a journal (a sweep store's, a fit's): what its rows were computed from,
// so that a later run resumes (or trusts) them only while it would write the same text. Lines:
//   # ...                         the first line: which kind of file it is (the caller's)
//   build ID                      the code (io/provenance.hpp's build ids)
//   PART I/N[ EXTRA]              the slice of the batch ("shard 0/4 cost-v1", "task 0/1")
//   KEY VALUE                     the caller's ("set 5e1c…", "spec …")
//   file HASH [ROLE ]PATH         FNV-1a 64 of a file's bytes (16 '-': unreadable), its role
//                                 (optional) and path relative to the batch file's folder
// The text is compared whole, so every caller's format is kept byte for byte; only how the
// lines are made is shared.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "io/shard.hpp"

namespace asperity {

inline constexpr std::string_view kInputsFileName = "inputs.txt";

class InputsFingerprint {
 public:
  InputsFingerprint(std::string_view first_line, std::string_view build_id, std::string_view part,
                    const io::Shard& shard, std::string_view extra = "");

  void add(std::string_view key, std::string_view value);  // "KEY VALUE"
  // "file HASH [ROLE ]PATH", HASH = hex16(digest()), or 16 '-' when digest() throws (a missing or
  // unreadable file: never equal to a hash).
  void add_file(std::string_view role, std::string_view relative_path, const std::function<std::uint64_t()>& digest);

  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

// DIR/inputs.txt's text; nothing when it is absent (read without following a link: "--out").
std::optional<std::string> read_inputs(const std::filesystem::path& dir);
// Writes DIR/inputs.txt durably (temp, fsync, rename, fsync of the folder).
void write_inputs(const std::filesystem::path& dir, const std::string& text);

}  // namespace asperity
