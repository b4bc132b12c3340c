#pragma once
// A campaign given to asperity.sweep as a Python dict: written into its store as the store's own
// campaign.yaml (every store keeps one), then swept like a file. Its relative scene paths are made
// absolute against `base` first, so the copy in the store names the same scenes wherever it lies.
#include <filesystem>

#include <yaml-cpp/yaml.h>

namespace asperity::python {

// Writes `tree` (a map of a campaign file's keys) as STORE/campaign.yaml and returns that path.
// STORE must be new, empty, or a sweep store whose campaign.yaml has the same text (a resume);
// else InputError (key "out"), and nothing is written. Never writes through a symbolic link.
std::filesystem::path campaign_into_store(YAML::Node tree, const std::filesystem::path& base,
                                          const std::filesystem::path& store);

}  // namespace asperity::python
