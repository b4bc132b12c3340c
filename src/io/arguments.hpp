#pragma once
// Checks of the arguments every front end takes (the command line's options, the Python
// module's keyword arguments), in one place so that both accept the same values and refuse the
// others with the same one-line message.
#include <string>
#include <string_view>

namespace asperity::io {

// Worker threads: 1 to 1024 (more than any node has; TBB fails on absurd counts).
inline constexpr int kMinThreads = 1, kMaxThreads = 1024;

// Hardware threads of this machine (at least 1).
int hardware_threads();

// "" when `text` is a decimal thread count in [kMinThreads, kMaxThreads]; else the message the
// command line gives, "Value TEXT not in range 1 to 1024" (CLI11's Range wording, kept).
std::string threads_problem(std::string_view text);

// The count `text` gives; InputError "ARGUMENT: Value TEXT not in range 1 to 1024" otherwise.
int checked_threads(std::string_view text, const std::string& argument);

// InputError "TEXT: ARGUMENT: holds a NUL byte ..." (the NUL shown as \0) when `text`, a path or
// a value from a caller that can pass one (Python; a command line cannot), holds a NUL byte:
// every system call, and the YAML of a --set value, would take the text as ending there.
void check_no_nul(std::string_view text, const std::string& argument);

}  // namespace asperity::io
