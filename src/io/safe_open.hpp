#pragma once
// Opening a file inside an output folder (a sweep store, a fit folder) so that nothing is ever
// read from or written to outside it: no symbolic link is followed, neither in the file's name nor
// in a folder between the output folder and it (each step is an openat with O_NOFOLLOW from the
// folder's descriptor), and only a regular file is accepted — a FIFO would block the reader (it
// opens non-blocking and checks with fstat), a device or socket is no result file. Anything else
// is bad input: one line naming the file.
#include <sys/types.h>

#include <filesystem>
#include <string>

namespace asperity::io {

// Opens `folder`/`rel` with `flags` (O_CREAT allowed; O_NOFOLLOW, O_CLOEXEC and, for the open
// itself, O_NONBLOCK are added). Returns the descriptor, or -1 with errno = ENOENT when the file
// (or a folder on its way) does not exist and O_CREAT was not asked. Throws InputError
// (file: the path, key: `key`) when the file or a folder on its way is a symbolic link or not a
// regular file / folder; std::runtime_error for any other failure.
int open_in_folder(const std::filesystem::path& folder, const std::filesystem::path& rel, int flags,
                   const std::string& key = "", mode_t mode = 0644);

// The same for `path`, whose folder is taken as the output folder (its last component only is
// guarded; use open_in_folder for files in subfolders).
int open_regular(const std::filesystem::path& path, int flags, const std::string& key = "", mode_t mode = 0644);

// Throws InputError like open_in_folder when a component of `rel` below `folder` exists and is
// not a real folder (a symbolic link, a file); absent components are fine (they will be made).
void check_real_folders(const std::filesystem::path& folder, const std::filesystem::path& rel,
                        const std::string& key = "");

// The whole text of `path` read through open_regular into `text`; false when it does not exist.
bool read_regular(const std::filesystem::path& path, std::string& text, const std::string& key = "");

}  // namespace asperity::io
