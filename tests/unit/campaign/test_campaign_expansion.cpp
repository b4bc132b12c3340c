// src/campaign: lazy expansion of a campaign into points (mixed radix), spaces, shards.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include "campaign/campaign.hpp"
#include "campaign/store.hpp"

using namespace asperity;

namespace {

Axis list_axis(const std::string& key, std::vector<double> xs) {
  Axis a;
  a.key = key;
  for (double x : xs) a.values.push_back(AxisValue{true, false, x, std::to_string(x)});
  return a;
}

Axis space_axis(const std::string& key, Axis::Kind kind, double a, double b, std::uint64_t n) {
  Axis ax;
  ax.key = key;
  ax.kind = kind;
  ax.a = a;
  ax.b = b;
  ax.n = n;
  return ax;
}

Campaign two_grid_campaign() {
  Campaign c;
  c.scenes = {"s0.yaml", "s1.yaml"};
  Grid g1;
  g1.name = "product";
  g1.axes = {list_axis("model.eta", {0, 50, 100}), list_axis("model.epsilon", {0.5, 0.7, 0.9, 0.99})};
  Grid g2;
  g2.name = "zip";
  g2.combine = Combine::zip;
  g2.axes = {space_axis("model.c_min", Axis::Kind::logspace, 1e-5, 1e-2, 4),
             space_axis("model.p", Axis::Kind::linspace, 1.0, 2.0, 4)};
  c.grids = {g1, g2};
  return c;
}

}  // namespace

TEST_CASE("campaign point count is the sum over grids of product or zip sizes times scenes", "[campaign]") {
  const Campaign c = two_grid_campaign();
  CHECK(c.grids[0].size() == 12);
  CHECK(c.grids[1].size() == 4);
  CHECK(c.size() == 2 * (12 + 4));
  CHECK(c.varied_keys() == std::vector<std::string>{"model.eta", "model.epsilon", "model.c_min", "model.p"});
}

TEST_CASE("product points follow nested loops with the last axis fastest and scenes slowest", "[campaign]") {
  const Campaign c = two_grid_campaign();
  const double eta[] = {0, 50, 100}, eps[] = {0.5, 0.7, 0.9, 0.99};
  std::uint64_t index = 0;
  for (std::size_t s = 0; s < 2; ++s)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j, ++index) {
        const Point p = point_at(c, index);
        CHECK(p.index == index);
        CHECK(p.grid == 0);
        CHECK(p.scene == s);
        REQUIRE(p.values.size() == 2);
        CHECK(p.values[0].axis->key == "model.eta");
        CHECK(p.values[0].value.number == eta[i]);
        CHECK(p.values[1].value.number == eps[j]);
      }
  CHECK(point_at(c, 24).grid == 1);
  CHECK_THROWS_AS(point_at(c, c.size()), std::out_of_range);
}

TEST_CASE("zip linspace and logspace points match their closed forms", "[campaign]") {
  const Campaign c = two_grid_campaign();
  for (std::uint64_t s = 0; s < 2; ++s)
    for (std::uint64_t k = 0; k < 4; ++k) {
      const Point p = point_at(c, 24 + s * 4 + k);
      CHECK(p.grid == 1);
      CHECK(p.scene == s);
      // logspace from 1e-5 to 1e-2 in 4 values: one decade per step.
      CHECK(p.values[0].value.number == Approx(std::pow(10.0, -5.0 + static_cast<double>(k))).epsilon(1e-14));
      // linspace 1..2 in 4 values: steps of 1/3.
      CHECK(p.values[1].value.number == Approx(1.0 + static_cast<double>(k) / 3.0).epsilon(1e-15));
    }
  // End points are exact, not rounded results of the formula.
  CHECK(point_at(c, 24).values[0].value.number == 1e-5);
  CHECK(point_at(c, 27).values[0].value.number == 1e-2);
  CHECK(point_at(c, 27).values[1].value.number == 2.0);
  CHECK(point_at(c, 27).values[1].value.text == "2");
}

TEST_CASE("a campaign of 1e9 points expands any index in constant memory", "[campaign]") {
  Campaign c;
  c.scenes = {"s.yaml"};
  Grid g;
  g.axes = {space_axis("model.eta", Axis::Kind::linspace, 0, 999, 1000),
            space_axis("model.epsilon", Axis::Kind::linspace, 0.001, 1.0, 1000),
            space_axis("model.p", Axis::Kind::linspace, 0, 999, 1000)};
  c.grids = {g};
  REQUIRE(c.size() == 1000000000ull);
  const std::uint64_t i = 123456789;  // digits 123 | 456 | 789 in radix 1000
  const Point p = point_at(c, i);
  CHECK(p.values[0].value.number == 123);
  CHECK(p.values[1].value.number == Approx(0.001 + 0.999 * 456.0 / 999.0).epsilon(1e-15));
  CHECK(p.values[2].value.number == 789);
  CHECK(point_at(c, c.size() - 1).values[1].value.number == 1.0);
}

TEST_CASE("shards partition the points: every index in exactly one shard", "[campaign]") {
  for (const std::uint64_t total : {0ull, 1ull, 7ull, 32ull, 101ull})
    for (const std::uint64_t n : {1ull, 2ull, 3ull, 8ull}) {
      std::vector<int> seen(total, 0);
      std::uint64_t sizes = 0;
      for (std::uint64_t i = 0; i < n; ++i) {
        const io::Shard s{i, n};
        std::uint64_t mine = 0;
        for (std::uint64_t k = 0; k < total; ++k)
          if (s.contains(k)) ++seen[k], ++mine;
        CHECK(s.size(total) == mine);
        sizes += mine;
      }
      CHECK(sizes == total);
      for (const int v : seen) CHECK(v == 1);
    }
}

TEST_CASE("shard text I/N is parsed strictly", "[campaign]") {
  CHECK(io::parse_shard("0/1").count == 1);
  CHECK(io::parse_shard("3/4").index == 3);
  for (const char* bad : {"4/4", "1", "/4", "1/0", "-1/4", "1/4x", "a/b", ""})
    CHECK_THROWS_AS(io::parse_shard(bad), std::invalid_argument);
}

TEST_CASE("shard auto (--shard auto) reads the SLURM array task", "[campaign][slurm]") {
  std::map<std::string, std::string> vars;
  const auto env = [&](const char* n) -> const char* {
    const auto it = vars.find(n);
    return it == vars.end() ? nullptr : it->second.c_str();
  };
  CHECK_THROWS_WITH(io::parse_shard("auto", env), Catch::Contains("SLURM_ARRAY_TASK_ID is not set"));
  // sbatch --array=1-4, the third task: shard 2/4.
  vars = {{"SLURM_ARRAY_TASK_ID", "3"},
          {"SLURM_ARRAY_TASK_MIN", "1"},
          {"SLURM_ARRAY_TASK_MAX", "4"},
          {"SLURM_ARRAY_TASK_COUNT", "4"}};
  const io::Shard s = io::parse_shard("auto", env);
  CHECK(s.index == 2);
  CHECK(s.count == 4);
  // --array=0-6:2 (not contiguous) would leave points of no task: refused.
  vars = {{"SLURM_ARRAY_TASK_ID", "2"},
          {"SLURM_ARRAY_TASK_MIN", "0"},
          {"SLURM_ARRAY_TASK_MAX", "6"},
          {"SLURM_ARRAY_TASK_COUNT", "4"}};
  CHECK_THROWS_WITH(io::parse_shard("auto", env), Catch::Contains("must be contiguous"));
  vars["SLURM_ARRAY_TASK_COUNT"] = "x7";
  CHECK_THROWS_WITH(io::parse_shard("auto", env), Catch::Contains("'x7', not a whole number"));
}

TEST_CASE("FNV-1a 64 matches the published test vectors", "[campaign]") {
  // Reference values of the FNV specification (draft-eastlake-fnv), independent of this code.
  CHECK(io::fnv1a64("") == 0xcbf29ce484222325ull);
  CHECK(io::fnv1a64("a") == 0xaf63dc4c8601ec8cull);
  CHECK(io::fnv1a64("foobar") == 0x85944171f73967e8ull);
  CHECK(io::hex16(0xaf63dc4c8601ec8cull) == "af63dc4c8601ec8c");
}

TEST_CASE("CSV fields with commas quotes and newlines survive a split", "[campaign]") {
  const std::vector<std::string> fields{"plain", "a,b", "say \"hi\"", "two\nlines", "", " pad "};
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    line += io::csv_field(fields[i]);
  }
  const auto back = io::csv_split(line);
  REQUIRE(back.size() == fields.size());
  CHECK(back[0] == "plain");
  CHECK(back[1] == "a,b");
  CHECK(back[2] == "say \"hi\"");
  CHECK(back[3] == "two lines");
  CHECK(back[4].empty());
  CHECK(back[5] == " pad ");
}
