#pragma once
// A sweep campaign as plain data (campaign/campaign_load.hpp reads it from YAML), and its lazy
// expansion into points: point index → (grid, base scene, one value per axis) by mixed radix, so
// a campaign of 10⁹ points needs memory for its axes only, never for its points.
//
// Point order (the index a store's rows are keyed by):
//   grids in file order; inside a grid, base scenes in file order (slowest), then the grid's
//   points: product → the last axis varies fastest (like nested loops in file order);
//   zip → the k-th value of every axis.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/shard.hpp"  // Shard, parse_shard: a campaign's --shard I/N (round robin over point indices)

namespace asperity {

class TopographyCache;

// One value an axis gives its key: a number (exact double) or text (a path, an enum name, a
// boolean spelled as in YAML). `text` is what the store prints (format_double for numbers).
struct AxisValue {
  bool is_number = false;
  bool is_yaml = false;  // `text` is a YAML list/map (set entries only, e.g. output.series: [])
  double number = 0;
  std::string text;
};

struct Axis {
  enum class Kind { list, linspace, logspace };
  std::string key;  // dotted scene key, e.g. model.eta
  Kind kind = Kind::list;
  std::vector<AxisValue> values;  // Kind::list
  double a = 0, b = 0;            // linspace / logspace end points (both included)
  std::uint64_t n = 0;            // linspace / logspace count
  int line = 0;                   // line of the key in the campaign file (for messages)

  std::uint64_t size() const { return kind == Kind::list ? values.size() : n; }
  // linspace: a + (b − a)·i/(n − 1); logspace: a·(b/a)^(i/(n − 1)) (end points given as values,
  // not exponents); the last value is b exactly; n = 1 gives a.
  AxisValue value(std::uint64_t i) const;
};

enum class Combine { product, zip };

struct Grid {
  std::string name;  // optional label (grid_<k> when not given)
  Combine combine = Combine::product;
  std::vector<Axis> axes;      // may be empty: one point (the base scenes as they are)
  std::uint64_t size() const;  // points per base scene
};

struct Campaign {
  std::string name;                                    // store folder name (default: file stem)
  std::filesystem::path file;                          // the campaign YAML
  std::vector<std::filesystem::path> scenes;           // base scenes (resolved against the file)
  std::vector<std::pair<std::string, AxisValue>> set;  // fixed overrides applied to every point
  std::vector<Grid> grids;
  bool series = false;      // also store each point's series.csv
  double time_limit_s = 0;  // wall-clock limit per point (0: none)
  // The contact solves of topography scenes (scene/topography_cache.hpp), shared by the campaign's
  // load checks, its store set-up and its points: each distinct surface and load is solved once
  // per process. Null: each CampaignScenes makes its own.
  std::shared_ptr<TopographyCache> topography;

  std::uint64_t size() const;  // total points (overflow checked at load)
  // Every key some grid varies, in first-appearance order: the store's value columns.
  std::vector<std::string> varied_keys() const;
};

struct PointValue {
  const Axis* axis = nullptr;
  AxisValue value;
};

struct Point {
  std::uint64_t index = 0;
  std::size_t grid = 0;
  std::size_t scene = 0;           // index into Campaign::scenes
  std::vector<PointValue> values;  // one per axis of the grid, in axis order
};

// index in [0, campaign.size()) → its point (std::out_of_range otherwise). O(axes + grids).
Point point_at(const Campaign& campaign, std::uint64_t index);

}  // namespace asperity
