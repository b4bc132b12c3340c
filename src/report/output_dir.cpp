#include "report/output_dir.hpp"

#include <sys/stat.h>

#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "io/digest.hpp"
#include "io/input_error.hpp"

namespace asperity {
namespace fs = std::filesystem;

fs::path normal_dir(const fs::path& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();
  return p;
}

namespace {

constexpr const char* kFilesLine = "files v2";

std::string marker_head(const std::string& command) {
  return "created by asperity " + command + "\n" + kFilesLine + "\n";
}

// What lstat says a path is (no symbolic link followed).
enum class Kind { absent, file, dir, other };
Kind kind_of(const fs::path& p) {
  struct stat st {};
  if (::lstat(p.c_str(), &st) != 0) return Kind::absent;
  if (S_ISREG(st.st_mode)) return Kind::file;
  if (S_ISDIR(st.st_mode)) return Kind::dir;
  return Kind::other;  // a symbolic link, FIFO, device or socket
}

// The file list of `dir`'s marker of `command`: relative path → the SHA-256 digests it was written
// with; nothing when the marker is missing, of another command, or has no list (written before
// lists existed, or made by hand).
std::optional<std::map<std::string, std::set<std::string>>> marker_files(const fs::path& dir,
                                                                         const std::string& command) {
  if (kind_of(dir) != Kind::dir || kind_of(dir / kMarkerFile) != Kind::file) return std::nullopt;
  std::ifstream in(dir / kMarkerFile, std::ios::binary);
  std::string line;
  if (!std::getline(in, line) || line != "created by asperity " + command) return std::nullopt;
  if (!std::getline(in, line) || line != kFilesLine) return std::nullopt;
  std::map<std::string, std::set<std::string>> files;
  while (std::getline(in, line)) {
    if (line.size() < 66 || line[64] != ' ') return std::nullopt;  // not ours: a damaged list
    files[line.substr(65)].insert(line.substr(0, 64));
  }
  return files;
}

void write_marker_files(const fs::path& dir, const std::string& command,
                        const std::map<std::string, std::set<std::string>>& files) {
  std::string text = marker_head(command);
  for (const auto& [path, digests] : files)
    for (const std::string& d : digests) text += d + " " + path + "\n";
  io::write_file_atomically(dir / kMarkerFile, text, io::Durability::synced);
}

[[noreturn]] void refuse(const fs::path& where, const std::string& option, const std::string& why) {
  throw io::InputError(where.string(), 0, option, why);
}

}  // namespace

void write_marker(const fs::path& dir, const std::string& command, bool file_list) {
  io::write_text_file(dir / kMarkerFile, file_list ? marker_head(command) : "created by asperity " + command + "\n");
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
  throw io::InputError(dir.string(), 0, option, "refusing to write there: " + why + "; choose a new or empty folder");
}

void claim_dir(const fs::path& dir, const std::string& command, const std::string& option,
               const std::function<bool(const fs::path&)>& legacy_ours, bool file_list) {
  check_ours(dir, command, option, legacy_ours);
  const fs::path target = normal_dir(dir);
  std::error_code ec;
  if (fs::exists(fs::symlink_status(target, ec))) {
    if (!has_marker(target, command)) write_marker(target, command, file_list);  // empty, or written before markers
    return;
  }
  fs::create_directories(target.parent_path(), ec);
  const std::string name = target.filename().string();
  const fs::path tmp = target.parent_path() / io::temp_name(name);
  io::remove_stale_temporaries(target.parent_path(), io::temp_prefix(name));
  const io::TempGuard on_signal(tmp);  // before it exists: a signal in between would leave it behind
  if (!fs::create_directory(tmp, ec) || ec)
    throw std::runtime_error("cannot create " + tmp.string() + ": " + ec.message());
  write_marker(tmp, command, file_list);
  fs::rename(tmp, target, ec);
  if (ec) {  // another process made it first: it must be ours too
    std::error_code e2;
    fs::remove_all(tmp, e2);
    check_ours(dir, command, option, legacy_ours);
    if (!has_marker(target, command)) write_marker(target, command, file_list);
  }
}

void check_publishable(const fs::path& dir, const std::string& command, const std::string& option) {
  const fs::path target = normal_dir(dir);
  const Kind k = kind_of(target);
  if (k == Kind::absent) return;
  std::error_code ec;
  if (k == Kind::dir && fs::is_empty(target, ec) && !ec) return;
  if (marker_files(target, command)) return;
  const std::string why = k == Kind::other  ? "it is a symbolic link or a special file"
                          : k == Kind::file ? "it is a file, not a folder"
                          : fs::exists(fs::symlink_status(target / kMarkerFile))
                              ? "its " + std::string(kMarkerFile) + " does not list the files asperity " + command +
                                    " wrote there (written by another command or version, or copied)"
                              : "it is not empty and was not written by asperity " + command;
  refuse(dir, option, "refusing to write there: " + why + "; choose a new or empty folder");
}

void publish_dir(const fs::path& dir, const std::string& command, const std::string& option,
                 const std::function<void(const fs::path&)>& fill) {
  check_publishable(dir, command, option);
  const fs::path target = normal_dir(dir);
  const fs::path parent = target.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create " + parent.string() + ": " + ec.message());
  const std::string own = io::temp_prefix(target.filename().string());  // starts our temporaries
  const fs::path tmp = parent / (own + "tmp-" + io::unique_tmp_suffix());
  // Temporaries of earlier writes whose process died (kill -9, a lost node): beside the folder
  // and inside it (it is ours: checked above).
  io::remove_stale_temporaries(parent, own);
  if (kind_of(target) == Kind::dir) io::remove_stale_temporaries(target);
  const io::TempGuard on_signal(tmp);  // before it exists: a signal in between would leave it behind
  if (!fs::create_directory(tmp, ec) || ec)
    throw std::runtime_error("cannot create " + tmp.string() + ": " + ec.message());
  struct Cleanup {  // the temporary folder goes whatever happens (renamed into place: nothing to do)
    fs::path p;
    ~Cleanup() {
      std::error_code e;
      fs::remove_all(p, e);
    }
  } cleanup{tmp};

  fill(tmp);

  // What was made: every regular file below tmp (fill's own marker, if any, aside).
  std::map<std::string, std::set<std::string>> made;
  for (auto it = fs::recursive_directory_iterator(tmp); it != fs::recursive_directory_iterator(); ++it) {
    if (!it->is_regular_file(ec) || it->is_symlink(ec)) continue;
    const std::string rel = it->path().lexically_relative(tmp).generic_string();
    if (rel == kMarkerFile) continue;
    made[rel].insert(io::sha256_file_hex(it->path()));
  }
  fs::remove(tmp / kMarkerFile, ec);

  if (kind_of(target) == Kind::absent) {  // a new folder: appears whole, marker included
    write_marker_files(tmp, command, made);
    fs::rename(tmp, target, ec);
    if (ec) throw std::runtime_error("cannot move " + tmp.string() + " to " + target.string() + ": " + ec.message());
    return;
  }

  // An existing folder: every file to write must be absent or ours as we left it, and the
  // folders on its way real folders.
  const std::map<std::string, std::set<std::string>> old =
      marker_files(target, command).value_or(std::map<std::string, std::set<std::string>>{});
  for (const auto& [rel, digest] : made) {
    fs::path at = target;
    const fs::path r(rel);
    for (auto part = r.begin(); part != r.end(); ++part) {
      at /= *part;
      const bool last = std::next(part) == r.end();
      const Kind k = kind_of(at);
      if (k == Kind::absent) break;
      if (!last && k != Kind::dir) refuse(at, option, "refusing to write through it: not a folder (a link or a file)");
      if (last) {
        const auto listed = old.find(rel);
        if (k != Kind::file || listed == old.end() || !listed->second.count(io::sha256_file_hex(at)))
          refuse(at, option,
                 "refusing to replace it: not a file asperity " + command +
                     " wrote there (added, edited or copied in); move it away or choose a new folder");
      }
    }
  }

  // Old and new contents listed while files move: an interruption leaves only listed files.
  std::map<std::string, std::set<std::string>> both = old;
  for (const auto& [rel, digests] : made) both[rel].insert(digests.begin(), digests.end());
  write_marker_files(target, command, both);
  for (const auto& [rel, digest] : made) {
    fs::create_directories((target / rel).parent_path(), ec);
    fs::rename(tmp / rel, target / rel, ec);
    if (ec)
      throw std::runtime_error("cannot move " + (tmp / rel).string() + " into " + target.string() + ": " +
                               ec.message());
  }
  // Files the last write made and this one did not: removed when still as written.
  for (const auto& [rel, digests] : old) {
    if (made.count(rel)) continue;
    const fs::path at = target / rel;
    bool real_path = true;  // no link on the way
    for (fs::path p = at.parent_path(); p != target && real_path; p = p.parent_path())
      real_path = kind_of(p) == Kind::dir;
    if (real_path && kind_of(at) == Kind::file && digests.count(io::sha256_file_hex(at))) {
      fs::remove(at, ec);
      for (fs::path p = at.parent_path(); p != target && fs::is_empty(p, ec); p = p.parent_path()) fs::remove(p, ec);
    }
  }
  write_marker_files(target, command, made);
}

}  // namespace asperity
