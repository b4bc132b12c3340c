#include "report/output_dir.hpp"

#include <fstream>
#include <stdexcept>
#include <system_error>

#include "io/input_error.hpp"

namespace asperity {
namespace fs = std::filesystem;

fs::path normal_dir(const fs::path& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();
  return p;
}

void write_marker(const fs::path& dir, const std::string& command) {
  scene_io::write_text_file(dir / kMarkerFile, "created by asperity " + command + "\n");
}

bool has_marker(const fs::path& dir, const std::string& command) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec))) return false;
  return first_line_is(dir / kMarkerFile, "created by asperity " + command);
}

bool first_line_is(const fs::path& file, const std::string& line) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(file, ec))) return false;
  std::ifstream f(file, std::ios::binary);
  std::string first;
  return static_cast<bool>(std::getline(f, first)) && first == line;
}

void check_ours(const fs::path& dir, const std::string& command, const std::string& option,
                const std::function<bool(const fs::path&)>& legacy_ours) {
  const fs::path target = normal_dir(dir);
  std::error_code ec;
  const auto st = fs::symlink_status(target, ec);
  if (!fs::exists(st)) return;
  if (fs::is_directory(st) && fs::is_empty(target, ec) && !ec) return;
  if (has_marker(target, command) || (fs::is_directory(st) && legacy_ours && legacy_ours(target))) return;
  const std::string why = fs::is_symlink(st)      ? "it is a symbolic link"
                          : !fs::is_directory(st) ? "it is a file, not a folder"
                                                  : "it is not empty and was not written by asperity " + command;
  throw InputError(dir.string(), 0, option, "refusing to write there: " + why + "; choose a new or empty folder");
}

void claim_dir(const fs::path& dir, const std::string& command, const std::string& option,
               const std::function<bool(const fs::path&)>& legacy_ours) {
  check_ours(dir, command, option, legacy_ours);
  const fs::path target = normal_dir(dir);
  std::error_code ec;
  if (fs::exists(fs::symlink_status(target, ec))) {
    if (!has_marker(target, command)) write_marker(target, command);  // empty, or written before markers
    return;
  }
  fs::create_directories(target.parent_path(), ec);
  const std::string name = target.filename().string();
  const fs::path tmp = target.parent_path() / ("." + name + ".tmp-" + unique_tmp_suffix());
  if (!fs::create_directory(tmp, ec) || ec) throw std::runtime_error("cannot create " + tmp.string() + ": " + ec.message());
  write_marker(tmp, command);
  fs::rename(tmp, target, ec);
  if (ec) {  // another process made it first: it must be ours too
    std::error_code e2;
    fs::remove_all(tmp, e2);
    check_ours(dir, command, option, legacy_ours);
    if (!has_marker(target, command)) write_marker(target, command);
  }
}

void write_dir_atomically(const fs::path& dir, const std::function<void(const fs::path&)>& check_replaceable,
                          const std::function<void(const fs::path&)>& fill) {
  const fs::path target = normal_dir(dir);
  const fs::path parent = target.parent_path();
  const std::string name = target.filename().string();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create " + parent.string() + ": " + ec.message());
  if (fs::exists(fs::symlink_status(target))) check_replaceable(target);  // before any work

  const fs::path tmp = parent / ("." + name + ".tmp-" + unique_tmp_suffix());
  fs::remove_all(tmp, ec);
  if (!fs::create_directory(tmp, ec) || ec)
    throw std::runtime_error("cannot create " + tmp.string() + ": " + ec.message());
  struct Cleanup {  // removes the temporary directory unless it was renamed into place
    fs::path p;
    bool armed = true;
    ~Cleanup() {
      std::error_code e;
      if (armed) fs::remove_all(p, e);
    }
  } cleanup{tmp};

  fill(tmp);

  // Replace: move an existing DIR aside, move the new one in, then delete the old one.
  fs::path old;
  if (fs::exists(fs::symlink_status(target))) {
    check_replaceable(target);
    old = parent / ("." + name + ".old-" + unique_tmp_suffix());
    fs::rename(target, old, ec);
    if (ec) throw std::runtime_error("cannot replace " + target.string() + ": " + ec.message());
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    std::error_code e2;
    if (!old.empty()) fs::rename(old, target, e2);  // put the previous one back
    throw std::runtime_error("cannot move " + tmp.string() + " to " + target.string() + ": " + ec.message());
  }
  cleanup.armed = false;
  if (!old.empty()) fs::remove_all(old, ec);
}

}  // namespace asperity
