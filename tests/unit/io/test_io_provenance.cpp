// io/provenance.hpp: what every result says about where it came from (build, command line,
// input files by content). A store's provenance.yaml: tests/unit/campaign/test_campaign_provenance.cpp.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>

#include "io/provenance.hpp"
#include "support_files.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::testing;

namespace {

std::string command_output(const std::string& cmd) {
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    ::pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

TEST_CASE("the provenance block names the build, the command and each input file's hash", "[io][provenance]") {
  const fs::path dir = temp_path("provenance");
  fs::create_directories(dir);
  const fs::path a = write_text(dir / "junctions.csv", "area_m2\n1e-9\n2e-9\n");
  const std::string command = "asperity run \"it's\" --set model.eta=5";
  const std::string text = io::provenance_yaml(
      command,
      {{"junctions", a}, {"junctions", dir / "." / "junctions.csv"}, {"measured", dir / "missing.csv"}, {"none", ""}});
  const YAML::Node p = YAML::Load(text)["provenance"];
  REQUIRE(p);
  CHECK(p["command_line"].as<std::string>() == command);  // quoted so that it reads back as is
  CHECK(p["asperity_version"].as<std::string>() == io::build_info().version);
  CHECK(p["git_commit"].as<std::string>() == io::build_info().git_commit);
  CHECK_THAT(p["libraries"].as<std::string>(), Catch::Contains("NLopt 2.") && Catch::Contains("TBB 20"));
  REQUIRE(p["files"].size() == 2);  // the same file once; an empty path not at all
  CHECK(p["files"][0]["role"].as<std::string>() == "junctions");
  CHECK(p["files"][0]["fnv1a64"].as<std::string>() == fnv1a64_hex("area_m2\n1e-9\n2e-9\n"));
  CHECK(p["files"][1]["fnv1a64"].as<std::string>() == "unreadable");
  fs::remove_all(dir);
}

TEST_CASE("the build's commit is the checkout's HEAD", "[io][provenance]") {
  const std::string head =
      command_output("git -C '" + std::string(ASPERITY_SOURCE_DIR) + "' rev-parse --short=12 HEAD 2>/dev/null");
  const std::string commit = io::build_info().git_commit;
  if (head.empty()) {
    CHECK(commit == "unknown");
  } else {
    // The binary may predate the last commit only if the build is stale; the test binary is
    // rebuilt with the library, so its commit is HEAD (with -dirty for local changes).
    CHECK(std::regex_match(commit, std::regex("[0-9a-f]{12}(-dirty)?")));
    CHECK(commit.substr(0, 12) == head);
  }
  CHECK_THAT(io::version_line(), Catch::Contains("commit " + commit));
}

TEST_CASE("result_path is relative inside the working directory and as given outside", "[io][provenance]") {
  CHECK(io::result_path(fs::current_path() / "a" / "b.csv") == "a/b.csv");
  CHECK(io::result_path("/nonexistent_root_dir/x.csv") == "/nonexistent_root_dir/x.csv");
}
