// A sweep store's provenance.yaml (campaign/sweep_store_provenance.hpp): the command and every
// input file by content.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "campaign/campaign_load.hpp"
#include "campaign/sweep.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

namespace {}  // namespace

TEST_CASE("a store's provenance names the command and the data each base scene reads", "[io][provenance][campaign]") {
  const fs::path data = fs::path(ASPERITY_SOURCE_DIR) / "tests" / "data";
  const Campaign c = load_campaign(data / "campaign" / "tiny.yaml");
  const fs::path out = temp_path("provenance_store");
  SweepOptions o;
  o.out = out;
  o.threads = 1;
  o.quiet = true;
  o.command_line = "asperity sweep tiny.yaml -j 1";
  run_sweep(c, o);
  const YAML::Node p = YAML::LoadFile((out / "provenance.yaml").string())["provenance"];
  REQUIRE(p);
  CHECK(p["command_line"].as<std::string>() == o.command_line);
  bool junctions = false;
  for (const auto& f : p["files"])
    if (f["role"].as<std::string>() == "junctions") {
      junctions = true;
      CHECK(f["fnv1a64"].as<std::string>() == fnv1a64_hex(slurp(data / "scene" / "exp_small" / "junctions.csv")));
    }
  CHECK(junctions);
  fs::remove_all(out);
}
