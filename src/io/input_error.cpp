#include "io/input_error.hpp"

#include <algorithm>
#include <utility>

namespace asperity::io {

InputError::InputError(std::string file_, int line_, std::string key_, std::string message_, int column_)
    : std::runtime_error(format(file_, line_, column_, key_, message_)),
      file(std::move(file_)),
      line(line_),
      column(column_),
      key(std::move(key_)),
      message(std::move(message_)) {}

std::string InputError::format(const std::string& file, int line, int column, const std::string& key,
                               const std::string& message) {
  std::string s = file;
  if (!file.empty() && line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  if (!key.empty()) s += (s.empty() ? "" : ": ") + key;
  s += (s.empty() ? "" : ": ") + message;
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  return s;
}

std::string input_path(const std::filesystem::path& file) { return file.lexically_normal().string(); }

}  // namespace asperity::io
