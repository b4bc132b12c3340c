#pragma once
// How a study's outputs name the command that wrote them: `asperity study FILE`, FILE the study
// file as the user gave it (studies/study_load.hpp), or just `asperity study` for options built
// in code.
#include <filesystem>
#include <string>

namespace asperity {

inline std::string study_command(const std::filesystem::path& study_file) {
  return study_file.empty() ? "asperity study" : "asperity study " + study_file.lexically_normal().generic_string();
}

}  // namespace asperity
