#pragma once
// Result directories written all at once: the files are made in a hidden temporary sibling that
// is renamed into place, so an interrupted or failed write never leaves a half-written directory
// (at worst a stale `.NAME.tmp-*` sibling). Shared by the run and fit writers.
#include <filesystem>
#include <functional>
#include <string>

namespace asperity {

// The directory a user means by `dir` ("runs/x/" and "runs/x" alike), made absolute.
std::filesystem::path normal_dir(const std::filesystem::path& dir);

// Writes `text` to `path` (no temporary: for files inside a directory being built). Throws
// std::runtime_error naming the path.
void write_file(const std::filesystem::path& path, const std::string& text);

// Replaces `dir` by a new directory filled by `fill(tmp)`. When `dir` exists,
// `check_replaceable(dir)` runs first and must throw if the directory is not ours to replace;
// the old directory is moved aside, put back if the new one cannot be moved in, and deleted
// after. Anything `fill` throws propagates, leaving `dir` untouched.
void write_dir_atomically(const std::filesystem::path& dir,
                          const std::function<void(const std::filesystem::path&)>& check_replaceable,
                          const std::function<void(const std::filesystem::path&)>& fill);

}  // namespace asperity
