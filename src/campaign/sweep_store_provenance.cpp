#include "campaign/sweep_store_provenance.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <charconv>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "batch/inputs_fingerprint.hpp"
#include "batch/parallel_runner.hpp"
#include "campaign/campaign_scenes.hpp"
#include "io/atomic_file.hpp"
#include "io/digest.hpp"
#include "io/hash.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/provenance.hpp"
#include "io/yaml_util.hpp"
#include "scene/input_files.hpp"
#include "scene/load.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// Whether the first point of any base scene runs on stand-in data (its experiment says so).
bool uses_stand_ins(const Campaign& c) {
  const CampaignScenes scenes(c);
  const std::uint64_t per_scene = c.grids.front().size();
  for (std::size_t s = 0; s < c.scenes.size(); ++s) {
    try {
      std::string d = scenes.scene(point_at(c, s * per_scene)).experiment.description;
      for (char& ch : d) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      if (d.find("stand-in") != std::string::npos) return true;
    } catch (const std::exception&) {
    }
  }
  return false;
}

// provenance.yaml of a new store: the campaign, shard, build and input files it was started with.
std::string store_provenance_yaml(const Campaign& c, const std::string& campaign_text, const SweepOptions& opt,
                                  ShardBalance balance) {
  std::ostringstream y;
  y << kStoreProvenanceFirstLine << '\n';
  y << "campaign: " << io::yaml_quoted(c.name) << '\n';
  y << "campaign_file: " << io::yaml_quoted(io::result_path(c.file)) << '\n';
  y << "campaign_fnv1a64: " << io::yaml_quoted(io::hex16(io::fnv1a64(campaign_text))) << '\n';
  y << "points: " << c.size() << '\n';
  y << "shard: " << io::yaml_quoted(std::to_string(opt.shard.index) + "/" + std::to_string(opt.shard.count)) << '\n';
  y << "shard_balance: " << io::yaml_quoted(shard_balance_name(balance)) << "  # how points are dealt to shards\n";
  y << "asperity_version: " << io::yaml_quoted(io::build_info().version) << '\n';
  y << "build_type: " << io::yaml_quoted(io::build_info().build_type) << '\n';
  y << "started_utc: " << io::yaml_quoted(utc_now()) << '\n';
  y << "stand_in_data: " << (uses_stand_ins(c) ? "true  # STAND-IN experiments, not measurements" : "false") << '\n';
  y << "hash: \"FNV-1a 64 of the resolved scene (scene_to_yaml, experiment file relative to the campaign folder) and "
       "of the bytes of its junctions and measured CSVs\"\n";
  // The input files as they were when the store started (each point's hash covers its own data,
  // so a resume after a CSV changed recomputes the points that use it and says so).
  std::vector<io::DataFile> files{{"campaign", c.file}};
  const CampaignScenes scenes(c);
  const std::uint64_t per_scene = c.grids.front().size();
  for (std::size_t s = 0; s < c.scenes.size(); ++s) {
    try {
      const std::vector<io::DataFile> f = input_files(scenes.scene(point_at(c, s * per_scene)));
      files.insert(files.end(), f.begin(), f.end());
    } catch (const std::exception&) {  // an invalid first point: its error is in the journal
    }
  }
  y << io::provenance_yaml(opt.command_line, files);
  return y.str();
}

// How a store's points are dealt to shards: its provenance.yaml's shard_balance (absent in
// stores written before it was recorded, which all dealt round robin).
ShardBalance recorded_balance(const std::string& provenance) {
  const std::string tag = "\nshard_balance: \"";
  const std::size_t at = provenance.find(tag);
  if (at == std::string::npos) return ShardBalance::index;
  const std::size_t from = at + tag.size();
  return parse_shard_balance(provenance.substr(from, provenance.find('"', from) - from));
}

// The first line of DIR/inputs.txt (batch/inputs_fingerprint.hpp), by which the files it lists are
// known as ours.
const std::string kInputsFirstLine =
    "# asperity sweep: the inputs every stored point's hash was checked against at the end of the last "
    "complete run (the next run trusts the stored hashes while this text is unchanged)";

}  // namespace

bool is_sweep_store_folder(const fs::path& dir) {
  std::error_code ec;
  const fs::path prov = dir / "provenance.yaml";
  if (fs::is_regular_file(fs::symlink_status(prov, ec))) {
    std::ifstream f(prov, std::ios::binary);
    std::string first;
    if (std::getline(f, first) && first == kStoreProvenanceFirstLine) return true;
  }
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string n = e.path().filename().string();
    if (n != ".lock" && n != "campaign.yaml" && n.find(".tmp") == std::string::npos) return false;
  }
  return true;
}

namespace sweep_detail {

void check_store_folder(const fs::path& dir) {
  if (!fs::is_directory(dir)) return;
  for (const auto& e : fs::directory_iterator(dir)) {
    static const std::string_view known[] = {".lock",      "campaign.yaml", "provenance.yaml", "journal.csv",
                                             "points.csv", "series",        "series.csv",      kInputsFileName};
    const std::string n = e.path().filename().string();
    if (std::find(std::begin(known), std::end(known), n) == std::end(known) && n.find(".tmp-") == std::string::npos &&
        e.path().extension() != ".png" && e.path().extension() != ".svg" && e.path().extension() != ".pdf" &&
        e.path().extension() != ".gp")  // figures drawn from the store and their kept scripts
      throw io::InputError(dir.string(), 0, "--out",
                           "refusing to use it as a sweep store: it holds '" + n + "', which no store holds");
  }
}

ShardBalance prepare_store(const fs::path& dir, const Campaign& c, const SweepOptions& opt) {
  const std::string text = io::read_file_text(c.file);
  const fs::path prov = dir / "provenance.yaml";
  if (fs::exists(prov)) {
    const std::string old = io::read_file_text(prov);
    const std::string want = "campaign_fnv1a64: " + io::yaml_quoted(io::hex16(io::fnv1a64(text)));
    if (old.find(want) == std::string::npos)
      throw std::runtime_error("the campaign file changed since " + dir.string() +
                               " was started (see its provenance.yaml); use another --out or remove the store");
    const ShardBalance had = recorded_balance(old);
    // Another plan would give this shard other points: the ones stored would be orphaned and
    // other shards' points run twice.
    if (opt.balance && *opt.balance != had && opt.shard.count > 1)
      throw io::InputError("", 0, "--balance",
                           shard_balance_name(*opt.balance) + ": " + dir.string() + " deals its points by " +
                               shard_balance_name(had) +
                               " (its provenance.yaml); every shard of a campaign must use the same --balance");
    return had;
  }
  // Cost by default; a campaign too large for a cost plan deals round robin unless asked (then refused).
  const ShardBalance balance =
      opt.balance.value_or(c.size() > kMaxCostBalancedPoints ? ShardBalance::index : ShardBalance::cost);
  io::write_file_durably(dir / "campaign.yaml", text);
  io::write_file_durably(prov, store_provenance_yaml(c, text, opt, balance));
  return balance;
}

std::string inputs_text(const Campaign& c, const std::string& build_id, const ShardPlan& plan,
                        const std::vector<fs::path>& files, FileHashes& hashes) {
  const io::Shard& shard = plan.shard();
  InputsFingerprint t(
      kInputsFirstLine, build_id, "shard", shard,
      plan.balance() == ShardBalance::index || shard.count == 1 ? std::string() : shard_balance_name(plan.balance()));
  // The effective `set` (the campaign's, then --set): --set changes points without changing the campaign text.
  for (const auto& [key, v] : c.set)
    t.add("set", io::hex16(io::fnv1a64(key + "\n" + std::to_string(v.is_number) + std::to_string(v.is_yaml) + "\n" +
                                       io::format_double(v.number) + "\n" + v.text)));
  const fs::path base = fs::absolute(c.file.parent_path()).lexically_normal();
  for (const fs::path& f : files)
    t.add_file("", f.lexically_relative(base).generic_string(), [&] { return hashes.of(f); });
  return t.text();
}

std::string take_points_digest(std::string& text) {
  const std::size_t at = text.rfind("\n" + kPointsDigestTag);
  if (at == std::string::npos || text.size() != at + 1 + kPointsDigestTag.size() + 64 + 1 || text.back() != '\n')
    return {};
  std::string digest = text.substr(at + 1 + kPointsDigestTag.size(), 64);
  text.resize(at + 1);
  return digest;
}

std::vector<fs::path> listed_inputs(const std::string& text, const Campaign& c) {
  std::vector<fs::path> files;
  if (text.rfind(kInputsFirstLine + "\n", 0) != 0) return files;
  const fs::path base = fs::absolute(c.file.parent_path()).lexically_normal();
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("file ", 0) == 0 && line.size() > 22) files.push_back((base / line.substr(22)).lexically_normal());
  return files;
}

std::uint64_t row_hash(const std::string& row) {
  const std::size_t a = row.find(',') + 1, b = row.find(',', a);
  std::uint64_t h = 0;
  std::from_chars(row.data() + a, row.data() + (b == std::string::npos ? row.size() : b), h, 16);
  return h;
}

std::vector<std::uint8_t> recheck_stored(const Campaign& c, const SweepOptions& opt, const ShardPlan& shard,
                                         const Journal& journal, FileHashes& data_hashes, const ParallelRunner& runner,
                                         std::uint64_t& rehashed_out) {
  const std::span<const StoredRow> stored = journal.entries();
  std::vector<std::uint8_t> current(stored.size(), 0);
  const fs::path base_dir = c.file.parent_path();
  std::vector<std::optional<CampaignScenes>> builders(static_cast<std::size_t>(runner.threads()));  // one a thread
  std::atomic<std::uint64_t> rehashed{0};
  runner.for_each_range(stored.size(), 256, [&](std::size_t begin, std::size_t end, int slot) {
    std::optional<CampaignScenes>& scenes = builders[static_cast<std::size_t>(slot)];
    if (!scenes) scenes.emplace(c);
    for (std::size_t i = begin; i != end; ++i) {
      const StoredRow& s = stored[i];
      if (s.index >= c.size() || !shard.contains(s.index)) continue;
      if (!s.ok() && opt.retry_failed) continue;  // rerun anyway
      ++rehashed;
      const Point p = point_at(c, s.index);
      const std::uint64_t stored_hash = row_hash(journal.row(s));  // pread: thread-safe
      try {
        // The typed scene first (no file read, no YAML), the checked one when it differs or has none.
        if (const auto quick = scenes->unchecked_scene(p))
          current[i] = io::fnv1a64(canonical_scene_text(*quick, base_dir, data_hashes)) == stored_hash;
        if (!current[i]) {
          std::uint64_t h = 0;
          try {
            h = io::fnv1a64(canonical_scene_text(scenes->scene(p), base_dir, data_hashes));
          } catch (const std::exception& e) {  // an invalid point is stored with the hash of its error
            h = io::fnv1a64("invalid point: " + std::string(e.what()));
          }
          current[i] = h == stored_hash;
        }
      } catch (const std::exception&) {
        current[i] = 0;  // the build stage reports it
      }
    }
  });
  rehashed_out = rehashed;
  return current;
}

void compact_series(SeriesFile& series, const Journal& journal) {
  bool stale = series.superseded();
  for (const SeriesBlock& b : series.blocks()) {
    const StoredRow* e = journal.find(b.index);
    stale = stale || !e || !e->ok();
  }
  if (stale)
    series.compact([&](std::uint64_t index, std::uint64_t hash) {
      const StoredRow* e = journal.find(index);
      return e && e->ok() && row_hash(journal.row(*e)) == hash;
    });
}

bool points_current(const SweepReport& rep, const std::string& points_digest) {
  const fs::path points_path = rep.store / "points.csv";
  if (!(rep.trusted && rep.ran == 0 && rep.dropped_lines == 0 && !points_digest.empty() &&
        fs::is_regular_file(fs::symlink_status(points_path))))
    return false;
  try {
    return io::sha256_file_hex(points_path) == points_digest;
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace sweep_detail

std::string SweepOptions::default_build_id() { return io::clean_build_id(); }

std::uint64_t FileHashes::of(const fs::path& file) {
  const std::string key = fs::absolute(file).lexically_normal().string();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (const auto it = by_path_.find(key); it != by_path_.end()) return it->second;
  return by_path_[key] = io::fnv1a64(io::read_file_text(file));
}

void FileHashes::note(const fs::path& file) {
  if (file.empty()) return;
  std::string key = fs::absolute(file).lexically_normal().string();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!noted_.insert(key).second) return;
  }
  // Hashed when first used, not at the end of the run: a file edited during a run must not be
  // recorded in inputs.txt with content no point was computed from.
  try {
    of(file);
  } catch (const std::exception&) {  // missing or unreadable: inputs_text records it as such
  }
}

std::vector<fs::path> FileHashes::inputs() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::set<std::string> all = noted_;
  for (const auto& [path, hash] : by_path_) all.insert(path);
  return {all.begin(), all.end()};
}

std::string canonical_scene_text(const Scene& scene, const fs::path& base_dir, FileHashes& data) {
  std::string text = scene_to_yaml(scene);
  const Experiment& e = scene.experiment;
  const fs::path& f = e.file;
  if (!f.empty()) {
    const std::string line = "  file: " + io::yaml_quoted(fs::absolute(f).lexically_normal().string()) + "\n";
    std::error_code ec;
    fs::path base = fs::weakly_canonical(fs::absolute(base_dir), ec);
    if (ec) base = fs::absolute(base_dir).lexically_normal();
    const std::string rel = fs::absolute(f).lexically_normal().lexically_relative(base).generic_string();
    const std::size_t at = text.find(line);
    if (at != std::string::npos) text.replace(at, line.size(), "  file: " + io::yaml_quoted(rel) + "\n");
  }
  // The data by content, not by name (an edited CSV keeps its name).
  data.note(scene.file);  // read into the text above
  data.note(f);
  text += "data:\n";
  text +=
      "  junctions_fnv1a64: " + io::yaml_quoted(e.junctions_file.empty() ? "" : io::hex16(data.of(e.junctions_file))) +
      "\n";
  text += "  measured_fnv1a64: " + io::yaml_quoted(e.measured_file.empty() ? "" : io::hex16(data.of(e.measured_file))) +
          "\n";
  // A topography scene's text holds its whole recipe; a measured height map is named by path, so
  // its bytes count too. Only then: other scenes keep their text (and stored hashes).
  if (const auto& t = scene.topography) {
    data.note(t->file);
    if (!t->map_file.empty())
      text += "  height_map_fnv1a64: " + io::yaml_quoted(io::hex16(data.of(t->map_file))) + "\n";
  }
  return text;
}

}  // namespace asperity
