#include "report/output_dir.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace asperity {
namespace fs = std::filesystem;

fs::path normal_dir(const fs::path& dir) {
  fs::path p = fs::absolute(dir).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();
  return p;
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw std::runtime_error("cannot create " + path.string());
  f << text;
  f.close();
  if (!f) throw std::runtime_error("cannot write " + path.string());
}

namespace {
std::string unique_suffix() {
  static std::atomic<unsigned> counter{0};
  return std::to_string(::getpid()) + "-" + std::to_string(counter++);
}
}  // namespace

void write_dir_atomically(const fs::path& dir, const std::function<void(const fs::path&)>& check_replaceable,
                          const std::function<void(const fs::path&)>& fill) {
  const fs::path target = normal_dir(dir);
  const fs::path parent = target.parent_path();
  const std::string name = target.filename().string();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create " + parent.string() + ": " + ec.message());
  if (fs::exists(fs::symlink_status(target))) check_replaceable(target);  // before any work

  const fs::path tmp = parent / ("." + name + ".tmp-" + unique_suffix());
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
    old = parent / ("." + name + ".old-" + unique_suffix());
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
