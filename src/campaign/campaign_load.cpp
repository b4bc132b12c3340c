#include "campaign/campaign_load.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/yaml_util.hpp"
#include "scene/load.hpp"
#include "scene/topography_cache.hpp"

namespace asperity {

namespace fs = std::filesystem;
using io::fail;
using io::format_double;
using io::has_control_char;
using io::load_yaml_file;
using io::MapView;
using io::node_kind;
using io::NumberParse;
using io::parse_double;
using io::parse_int;
using io::quote;
using io::Source;
using io::trim;

namespace {

const std::vector<std::string> kCampaignKeys{"name",   "description", "scene",   "scenes", "set",
                                             "series", "time_limit",  "combine", "axes",   "grids"};
const std::vector<std::string> kGridKeys{"name", "combine", "axes"};

int line_of(const YAML::Node& n) {
  if (!n.IsDefined()) return 0;
  const YAML::Mark m = n.Mark();
  return m.is_null() ? 0 : m.line + 1;
}

// The (key node, value node) pairs of a map whose keys are free (dotted scene keys), with the
// checks MapView does for fixed keys: a map, scalar keys, no duplicates.
std::vector<std::pair<YAML::Node, YAML::Node>> free_map(const MapView& parent, const YAML::Node& n,
                                                        const std::string& k) {
  if (!n.IsMap()) parent.fail_at(n, k, "expected a map of 'scene.key: values' entries, got " + node_kind(n));
  std::vector<std::pair<YAML::Node, YAML::Node>> out;
  for (auto it = n.begin(); it != n.end(); ++it) {
    if (!it->first.IsScalar())
      parent.fail_at(it->first, k, "keys must be dotted scene keys, got " + node_kind(it->first));
    for (const auto& e : out)
      if (e.first.Scalar() == it->first.Scalar())
        fail(parent.source(), it->first, parent.key(k) + "." + it->first.Scalar(),
             "duplicate key (first given at line " + std::to_string(line_of(e.first)) + ")");
    out.emplace_back(it->first, it->second);
  }
  return out;
}

// One scalar as an axis/set value: a plain number, or text; numbers with units are rejected.
AxisValue scalar_value(const Source& src, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar()) fail(src, n, key, "values must be single numbers or texts, got " + node_kind(n));
  AxisValue v;
  v.text = n.Scalar();
  double x = 0;
  switch (parse_double(n.Scalar(), x)) {
    case NumberParse::ok:
      v.is_number = true;
      v.number = x;
      v.text = format_double(x);
      break;
    case NumberParse::has_unit:
      fail(src, n, key, "expected a plain number in SI units, got " + quote(n.Scalar()));
    case NumberParse::not_finite:
      fail(src, n, key, "must be a finite number, got " + quote(n.Scalar()));
    default:
      if (trim(n.Scalar()).empty()) fail(src, n, key, "empty value");
      break;
  }
  return v;
}

Axis parse_axis(const Source& src, const YAML::Node& kn, const YAML::Node& vn) {
  Axis ax;
  ax.key = kn.Scalar();
  ax.line = line_of(kn);
  auto fail_here = [&](const YAML::Node& at, const std::string& msg) {
    fail(src, at.IsDefined() && !at.IsNull() && line_of(at) > 0 ? at : kn, ax.key, msg);
  };
  if (vn.IsSequence()) {
    if (vn.size() == 0) fail_here(kn, "empty axis (give at least one value)");
    for (const auto& item : vn) {
      AxisValue v = scalar_value(src, item, ax.key);
      for (const auto& prev : ax.values) {
        if (prev.is_number != v.is_number)
          fail_here(item, "mixed numbers and texts in one axis (" + quote(prev.text) + " and " + quote(v.text) + ")");
        if (prev.text == v.text) fail_here(item, "value " + quote(v.text) + " listed twice");
      }
      ax.values.push_back(std::move(v));
    }
    return ax;
  }
  if (vn.IsMap()) {
    const MapView m(src, vn, ax.key, {"linspace", "logspace"});
    const auto lin = m.find("linspace");
    const auto log = m.find("logspace");
    if (!lin && !log) fail_here(kn, "empty axis: expected {linspace: [a, b, n]} or {logspace: [a, b, n]}");
    if (lin && log) fail_here(kn, "give either linspace or logspace, not both");
    const std::string which = lin ? "linspace" : "logspace";
    const YAML::Node spec = lin ? *lin : *log;
    ax.kind = lin ? Axis::Kind::linspace : Axis::Kind::logspace;
    if (!spec.IsSequence() || spec.size() != 3)
      m.fail_at(spec, which, "expected [first, last, count], got " + node_kind(spec));
    ax.a = m.number(spec[0], which, nullptr);
    ax.b = m.number(spec[1], which, nullptr);
    int n = 0;
    if (!spec[2].IsScalar() || !parse_int(spec[2].Scalar(), n))
      m.fail_at(spec[2], which, "count must be an integer, got " + node_kind(spec[2]));
    if (n < 1) m.fail_at(spec[2], which, "empty axis: count must be >= 1, got " + std::to_string(n));
    if (n > 1 && ax.a == ax.b) m.fail_at(spec, which, "first == last with count > 1 repeats one value");
    if (ax.kind == Axis::Kind::logspace && !(ax.a * ax.b > 0))
      m.fail_at(
          spec, which,
          "end points must be non-zero and of one sign, got " + format_double(ax.a) + " and " + format_double(ax.b));
    ax.n = static_cast<std::uint64_t>(n);
    return ax;
  }
  fail_here(vn, "expected a list of values, {linspace: [a, b, n]} or {logspace: [a, b, n]}, got " + node_kind(vn));
  std::abort();  // fail_here throws
}

std::uint64_t checked_mul(std::uint64_t a, std::uint64_t b, const Source& src, const YAML::Node& at,
                          const std::string& key) {
  constexpr std::uint64_t cap = std::uint64_t(1) << 62;
  if (b != 0 && a > cap / b) fail(src, at, key, "too many points (more than 2^62)");
  return a * b;
}

Grid parse_grid(const Source& src, const MapView& m, const std::string& name) {
  Grid g;
  g.name = name;
  if (auto n = m.find("combine"))
    g.combine = m.enumeration<Combine>(*n, "combine", {{"product", Combine::product}, {"zip", Combine::zip}});
  const YAML::Node axes = m.require("axes");
  const auto entries = free_map(m, axes, "axes");
  if (entries.empty()) m.fail_at(axes, "axes", "empty: give at least one axis");
  for (const auto& [kn, vn] : entries) g.axes.push_back(parse_axis(src, kn, vn));
  if (g.combine == Combine::zip)
    for (std::size_t i = 1; i < g.axes.size(); ++i)
      if (g.axes[i].size() != g.axes[0].size())
        fail(src, entries[i].first, g.axes[i].key,
             "zip needs axes of equal length: " + std::to_string(g.axes[i].size()) + " values here, " +
                 std::to_string(g.axes[0].size()) + " in " + g.axes[0].key + " (line " +
                 std::to_string(g.axes[0].line) + ")");
  std::uint64_t s = 1;
  for (const Axis& ax : g.axes) s = checked_mul(s, ax.size(), src, axes, m.key("axes"));
  return g;
}

// The keys of the campaign itself: name, description, series, time_limit.
void read_campaign_keys(const MapView& m, Campaign& c) {
  if (auto n = m.find("name")) {
    c.name = m.string(*n, "name");
    const bool ok = !c.name.empty() && c.name.find_first_of("/\\") == std::string::npos && c.name != "." &&
                    c.name != ".." && !has_control_char(c.name);
    if (!ok) m.fail_at(*n, "name", "must be a plain folder name (no '/', no control characters), got " + quote(c.name));
  }
  if (auto n = m.find("description")) m.string(*n, "description");
  if (auto n = m.find("series")) c.series = m.boolean(*n, "series");
  if (auto n = m.find("time_limit")) {
    c.time_limit_s = m.number(*n, "time_limit", "s");
    if (!(c.time_limit_s > 0))
      m.fail_at(*n, "time_limit", "must be > 0 (seconds of wall time per point), got " + format_double(c.time_limit_s));
  }
}

// `scene:` or `scenes:`, each file checked to exist once.
void read_base_scenes(const MapView& m, const fs::path& yaml, Campaign& c) {
  const auto one = m.find("scene");
  const auto many = m.find("scenes");
  if (one && many) m.fail_at(*many, "scenes", "give either scene or scenes, not both");
  if (!one && !many) m.require("scenes");
  std::vector<std::string> scene_texts;
  if (one) scene_texts.push_back(m.string(*one, "scene"));
  if (many) {
    scene_texts = m.string_list(*many, "scenes");
    if (scene_texts.empty()) m.fail_at(*many, "scenes", "empty list: give at least one scene");
  }
  for (std::size_t i = 0; i < scene_texts.size(); ++i) {
    const YAML::Node at = one ? *one : (*many)[i];
    const std::string k = one ? "scene" : "scenes";
    const fs::path p = yaml.parent_path() / scene_texts[i];
    std::error_code ec;
    if (!fs::is_regular_file(p, ec))
      m.fail_at(at, k, "scene file not found: " + quote(scene_texts[i]) + " (looked for " + io::input_path(p) + ")");
    for (const auto& q : c.scenes)
      if (fs::equivalent(q, p, ec)) m.fail_at(at, k, "scene " + quote(scene_texts[i]) + " listed twice");
    c.scenes.push_back(p.lexically_normal());
  }
}

// `set:`: the fixed overrides into c.set; the line of each.
std::vector<int> read_set(const Source& src, const MapView& m, Campaign& c) {
  std::vector<int> set_lines;
  if (auto n = m.find("set")) {
    for (const auto& [kn, vn] : free_map(m, *n, "set")) {
      if (vn.IsSequence() || vn.IsMap()) {  // e.g. output.series: [t, Q]; checked by the scene loader
        YAML::Emitter e;
        e << YAML::Flow << vn;
        c.set.emplace_back(kn.Scalar(), AxisValue{false, true, 0, e.c_str()});
      } else {
        c.set.emplace_back(kn.Scalar(), scalar_value(src, vn, "set." + kn.Scalar()));
      }
      set_lines.push_back(line_of(kn));
    }
  }
  return set_lines;
}

// `axes:` (one grid), `grids:`, or neither (the base scenes only).
void read_grids(const Source& src, const MapView& m, Campaign& c) {
  const auto axes = m.find("axes");
  const auto grids = m.find("grids");
  if (axes && grids) m.fail_at(*grids, "grids", "give either axes (one grid) or grids, not both");
  if (grids) {
    if (!grids->IsSequence() || grids->size() == 0)
      m.fail_at(*grids, "grids", "expected a non-empty list of {name, combine, axes} maps, got " + node_kind(*grids));
    if (m.find("combine")) m.fail_at(*m.find("combine"), "combine", "with grids, give combine inside each grid");
    for (std::size_t i = 0; i < grids->size(); ++i) {
      const MapView gm(src, (*grids)[i], "grids[" + std::to_string(i) + "]", kGridKeys, line_of(*grids));
      std::string name = "grid_" + std::to_string(i);
      if (auto n = gm.find("name")) {
        name = gm.string(*n, "name");
        if (has_control_char(name))
          gm.fail_at(*n, "name", "must not hold control characters (newline, tab, ...), got " + quote(name));
      }
      c.grids.push_back(parse_grid(src, gm, name));
    }
  } else if (axes) {
    c.grids.push_back(parse_grid(src, m, "grid_0"));
  } else {
    if (auto n = m.find("combine")) m.fail_at(*n, "combine", "combine without axes");
    c.grids.push_back(Grid{"base", Combine::product, {}});  // just the base scenes
  }
}

// Every list value and both end points of every space on the first base scene (unknown keys,
// out-of-range values), each error at its axis's line.
void probe_axes(const Campaign& c, const std::string& display) {
  const CampaignScenes scenes(c);
  for (std::size_t gi = 0; gi < c.grids.size(); ++gi)
    for (const Axis& ax : c.grids[gi].axes) {
      std::vector<std::uint64_t> probe;
      if (ax.kind == Axis::Kind::list)
        for (std::uint64_t i = 0; i < ax.size(); ++i) probe.push_back(i);
      else
        probe = {0, ax.size() - 1};
      for (const std::uint64_t i : probe) {
        try {
          scenes.scene(Point{0, gi, 0, {PointValue{&ax, ax.value(i)}}});
        } catch (const io::InputError& e) {
          rethrow_at_campaign_line(e, display, ax.line, ax.key);
        }
      }
    }
}

}  // namespace

Campaign load_campaign(const fs::path& yaml) {
  const std::string display = io::input_path(yaml);
  const Source src{display, nullptr};
  const YAML::Node root = load_yaml_file(yaml, display);
  const MapView m(src, root, "", kCampaignKeys, 1);

  Campaign c;
  c.topography = std::make_shared<TopographyCache>();
  c.file = fs::absolute(yaml).lexically_normal();
  c.name = yaml.stem().string();
  read_campaign_keys(m, c);
  read_base_scenes(m, yaml, c);
  const std::vector<int> set_lines = read_set(src, m, c);
  read_grids(src, m, c);
  std::uint64_t total = 0;
  for (const Grid& g : c.grids) {
    total += checked_mul(g.size(), c.scenes.size(), src, root, "grids");
    if (total > (std::uint64_t(1) << 62)) fail(src, root, "grids", "too many points (more than 2^62)");
  }

  // Keys given both as set and as an axis are a mistake (the axis would silently win).
  for (const Grid& g : c.grids)
    for (const Axis& ax : g.axes)
      for (std::size_t i = 0; i < c.set.size(); ++i)
        if (c.set[i].first == ax.key)
          throw io::InputError(display, ax.line, ax.key,
                               "also fixed by set (line " + std::to_string(set_lines[i]) + "); keep one");

  // Semantic checks against the scenes: every base scene with `set`, then every axis value.
  check_base_scenes(c, set_lines);
  probe_axes(c, display);
  return c;
}

}  // namespace asperity
