#include "batch/inputs_fingerprint.hpp"

#include "io/atomic_file.hpp"
#include "io/hash.hpp"
#include "io/safe_open.hpp"

namespace asperity {

InputsFingerprint::InputsFingerprint(std::string_view first_line, std::string_view build_id, std::string_view part,
                                     const io::Shard& shard, std::string_view extra) {
  text_.append(first_line).append("\nbuild ").append(build_id).append("\n").append(part).append(" ");
  text_.append(std::to_string(shard.index)).append("/").append(std::to_string(shard.count));
  if (!extra.empty()) text_.append(" ").append(extra);
  text_ += '\n';
}

void InputsFingerprint::add(std::string_view key, std::string_view value) {
  text_.append(key).append(" ").append(value).append("\n");
}

void InputsFingerprint::add_file(std::string_view role, std::string_view relative_path,
                                 const std::function<std::uint64_t()>& digest) {
  std::string sum(16, '-');
  try {
    sum = io::hex16(digest());
  } catch (const std::exception&) {
  }
  text_.append("file ").append(sum).append(" ");
  if (!role.empty()) text_.append(role).append(" ");
  text_.append(relative_path).append("\n");
}

std::optional<std::string> read_inputs(const std::filesystem::path& dir) {
  std::string text;
  if (!io::read_regular(dir / kInputsFileName, text, "--out")) return std::nullopt;
  return text;
}

void write_inputs(const std::filesystem::path& dir, const std::string& text) {
  io::write_file_durably(dir / kInputsFileName, text);
}

}  // namespace asperity
