#pragma once
// Result directories written all at once: the files are made in a hidden temporary sibling that
// is renamed into place, so an interrupted or failed write never leaves a half-written directory
// (at worst a stale `.NAME.tmp-*` sibling). Shared by the run and fit writers.
#include <filesystem>
#include <functional>
#include <string>

#include "io/atomic_file.hpp"  // io::write_text_file: the files inside such a directory

namespace asperity {

// The directory a user means by `dir` ("runs/x/" and "runs/x" alike), made absolute.
std::filesystem::path normal_dir(const std::filesystem::path& dir);

// Every folder a command creates carries a marker file, `.asperity`, holding
// "created by asperity COMMAND". A command writes into, or replaces, an existing folder only when
// it is empty or carries the marker of the same command (or, for folders written before the marker
// existed, `legacy_ours(dir)` recognises it); anything else is refused, so no command overwrites a
// folder or file it did not create.
inline constexpr const char* kMarkerFile = ".asperity";

// Writes the marker of `command` into `dir`; with `file_list`, as publish_dir keeps it (a list of
// the files written there, empty for now).
void write_marker(const std::filesystem::path& dir, const std::string& command, bool file_list = false);

// True when `dir` exists, is a real directory (not a symlink) and carries the marker of `command`.
bool has_marker(const std::filesystem::path& dir, const std::string& command);

// Throws InputError (file: the folder, key: `option`, e.g. "--out"; exit 2 in the CLI) unless
// `dir` is absent, an empty directory, carries the marker of `command`, or `legacy_ours(dir)`.
void check_ours(const std::filesystem::path& dir, const std::string& command, const std::string& option,
                const std::function<bool(const std::filesystem::path&)>& legacy_ours = {});

// check_ours(dir, ...), then makes sure `dir` exists and carries the marker of `command`: an absent
// folder is made as a hidden sibling holding the marker and renamed into place, so processes
// starting together (array tasks sharing one output folder) never see a folder without it.
void claim_dir(const std::filesystem::path& dir, const std::string& command, const std::string& option,
               const std::function<bool(const std::filesystem::path&)>& legacy_ours = {}, bool file_list = false);

// True when the first line of `file` is `line` (recognises files we wrote before markers).
bool first_line_is(const std::filesystem::path& file, const std::string& line);

// Writes the files `fill(tmp)` makes in a temporary folder into `dir`, replacing only what the
// same command wrote there before: the folder's marker lists every file it wrote with its SHA-256
// ("created by asperity COMMAND", "files v2", then "SHA256 RELATIVE/PATH" lines). Before anything
// moves, each file to be written must be absent or listed with its current content (a file the
// user added, edited or copied in is foreign: InputError naming it, key `option`, nothing
// changed); `dir` must be absent, empty, or carry such a list (a marker without one, or a folder
// that merely looks like a run or fit folder, is refused). Files are then renamed into place one
// by one under a marker listing old and new contents (so an interruption never makes our files
// look foreign), files of the last write that this one did not make are removed when unchanged,
// and the marker is rewritten with the new list. Foreign files and folders stay untouched; no
// path under `dir` is followed through a symbolic link.
void publish_dir(const std::filesystem::path& dir, const std::string& command, const std::string& option,
                 const std::function<void(const std::filesystem::path&)>& fill);

// check_ours for publish_dir's rule: `dir` absent, an empty directory, or a real directory whose
// marker of `command` lists its files (InputError naming `dir` and `option` otherwise).
void check_publishable(const std::filesystem::path& dir, const std::string& command, const std::string& option);

}  // namespace asperity
