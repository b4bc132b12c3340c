#include "io/provenance.hpp"

#include <set>
#include <sstream>
#include <system_error>

#include "build_config.hpp"  // generated at configure time (CMakeLists.txt)
#include "git_commit.hpp"    // generated at every build (cmake/git_commit.cmake)
#include "io/atomic_file.hpp"
#include "io/hash.hpp"
#include "io/yaml_util.hpp"

namespace asperity::io {

namespace fs = std::filesystem;

namespace {

std::string compiler_text() {
#if defined(__clang__)
  return "Clang " + std::to_string(__clang_major__) + "." + std::to_string(__clang_minor__) + "." +
         std::to_string(__clang_patchlevel__);
#elif defined(__GNUC__)
  return "GCC " + std::to_string(__GNUC__) + "." + std::to_string(__GNUC_MINOR__) + "." +
         std::to_string(__GNUC_PATCHLEVEL__);
#else
  return "unknown compiler";
#endif
}

}  // namespace

BuildInfo build_info() {
  return BuildInfo{ASPERITY_VERSION, ASPERITY_GIT_COMMIT, ASPERITY_BUILD_TYPE, compiler_text(), ASPERITY_LIBRARIES};
}

std::string clean_build_id() {
  const BuildInfo b = build_info();
  if (b.git_commit.empty() || b.git_commit == "unknown" || b.git_commit.find("dirty") != std::string::npos) return "";
  return "asperity " + b.version + " commit " + b.git_commit + " " + b.build_type + " " + b.compiler;
}

std::string code_build_id() {
  if (std::string id = clean_build_id(); !id.empty()) return id;
  const BuildInfo b = build_info();
  try {
    return "asperity " + b.version + " commit " + b.git_commit + " " + b.build_type + " " + b.compiler +
           " executable " + hex16(fnv1a64(read_file_text("/proc/self/exe")));
  } catch (const std::exception&) {  // no /proc: nothing names this code
    return "";
  }
}

std::string version_line() {
  const BuildInfo b = build_info();
  return "asperity " + b.version + " (commit " + b.git_commit + ", " + b.build_type + ", " + b.compiler + ")";
}

std::string result_path(const fs::path& file) {
  std::error_code ec;
  const fs::path rel = fs::relative(file, ec);
  const bool inside = !ec && !rel.empty() && rel.begin()->string() != "..";
  return (inside ? rel : file).generic_string();
}

std::string provenance_yaml(const std::string& command_line, const std::vector<DataFile>& files) {
  const BuildInfo b = build_info();
  std::ostringstream y;
  y << "provenance:\n";
  y << "  asperity_version: " << yaml_quoted(b.version) << '\n';
  y << "  git_commit: " << yaml_quoted(b.git_commit) << '\n';
  y << "  build_type: " << yaml_quoted(b.build_type) << '\n';
  y << "  compiler: " << yaml_quoted(b.compiler) << '\n';
  y << "  libraries: " << yaml_quoted(b.libraries) << '\n';
  y << "  command_line: " << yaml_quoted(command_line) << '\n';
  y << "  files:  # FNV-1a 64 of each input file's bytes\n";
  std::set<std::string> seen;
  bool any = false;
  for (const DataFile& f : files) {
    if (f.path.empty()) continue;
    const std::string shown = result_path(f.path);
    if (!seen.insert(fs::absolute(f.path).lexically_normal().string()).second) continue;
    std::string hash = "unreadable";
    try {
      hash = hex16(fnv1a64(read_file_text(f.path)));
    } catch (const std::exception&) {
    }
    y << "    - {role: " << yaml_quoted(f.role) << ", path: " << yaml_quoted(shown)
      << ", fnv1a64: " << yaml_quoted(hash) << "}\n";
    any = true;
  }
  if (!any) y << "    []\n";
  return y.str();
}

}  // namespace asperity::io
