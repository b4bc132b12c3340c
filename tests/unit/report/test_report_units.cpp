// report/units.hpp: docs/units.md is generated from the tables and cannot drift from them.
#include <catch2/catch.hpp>
#include <filesystem>

#include "report/units.hpp"
#include "scene/scene.hpp"
#include "support_files.hpp"

using namespace asperity;

TEST_CASE("docs/units.md equals the units the tables give", "[report][units]") {
  const std::string committed = testing::slurp(std::filesystem::path(ASPERITY_SOURCE_DIR) / "docs" / "units.md");
  // To refresh after a table changed: build, then write units_reference_markdown() to the file.
  CHECK(committed == units_reference_markdown());
  // Every series column has a unit row.
  for (const std::string& c : all_series()) CHECK(committed.find("| `" + c + "` | ") != std::string::npos);
}
