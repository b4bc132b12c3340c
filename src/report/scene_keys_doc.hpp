#pragma once
// docs/scene_keys.md: every scene key with its kind, unit, allowed range, default and why its
// limit is there, generated from the one key table (scene/scene_keys.hpp); a test keeps the
// committed file equal to it, so the manual cannot drift from what the loader checks.
#include <string>

namespace asperity {

std::string scene_keys_markdown();

}  // namespace asperity
