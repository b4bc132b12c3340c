// report/scene_keys_doc.hpp: docs/scene_keys.md is generated from the key table and cannot drift.
#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>

#include "report/scene_keys_doc.hpp"
#include "scene/scene_keys.hpp"
#include "support_files.hpp"

using namespace asperity;

TEST_CASE("docs/scene_keys.md equals the key table", "[report][keys]") {
  const std::filesystem::path file = std::filesystem::path(ASPERITY_SOURCE_DIR) / "docs" / "scene_keys.md";
  const std::string now = scene_keys_markdown();
  // To refresh after the table changed: ASPERITY_REFRESH_DOCS=1 build/asperity_tests "[keys]".
  if (std::getenv("ASPERITY_REFRESH_DOCS")) testing::write_text(file, now);
  const std::string committed = testing::slurp(file);
  CHECK(committed == now);
  // One row per key, with the loader's own range text for the numbers.
  for (const SceneKey& k : scene_keys()) {
    CHECK(committed.find("| `" + std::string(k.name) + "` |") != std::string::npos);
    if (k.range) CHECK(committed.find(k.range) != std::string::npos);
  }
}
