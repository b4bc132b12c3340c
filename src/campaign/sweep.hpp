#pragma once
// Runs the points of a campaign (or of one shard of it) into a result store (store.hpp), in
// parallel, resuming whatever the store already holds.
//
// Parallelism: the pipeline of batch/parallel_runner.hpp (a task arena of `threads` threads):
//   1. serial: next point of the shard → canonical hash of its scene; points already in the
//      journal with the same hash are skipped. A stored point is first tried with the typed
//      scene (CampaignScenes::unchecked_scene: no file read, no YAML), so a no-op resume costs
//      microseconds per point; otherwise the checked scene is built (typed fields set on a base
//      scene loaded once, CampaignScenes::scene) and the data files' bytes are hashed once per
//      file per sweep;
//   2. parallel: simulate (one model instance per point; threads pick up the next point as soon
//      as they are free, so uneven run times balance); OpenMP is set to 1 thread in here: the
//      cores are already busy with points, and an OpenMP team per point would oversubscribe them
//      (and an OpenMP reduction's order would depend on the team size);
//   3. serial, out of order: append the row to the journal (write, and fdatasync once per group
//      of points: SweepOptions::sync), progress.
// At most 2·threads points are in flight: memory does not grow with the campaign.
//
// Cancel (SweepOptions::stop): the build stage starts no point once it is set, and every point
// in flight polls it (batch/stop_flag.hpp) and stops within ~0.05 s without a row, so it reruns next time.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "campaign/campaign.hpp"
#include "campaign/shard_plan.hpp"
#include "campaign/store.hpp"
#include "scene/scene.hpp"

namespace asperity {

// The first line of a store's provenance.yaml, by which a store's folder is known as asperity's.
inline constexpr const char* kStoreProvenanceFirstLine =
    "# asperity sweep store: written once, when the store was started";

// Whether the folder `dir` (which exists) may take a sweep store: a store already (its
// provenance.yaml's first line), or what a sweep killed at its very start leaves (.lock,
// campaign.yaml, temporaries). For check_ours of the command line and the Python module.
bool is_sweep_store_folder(const std::filesystem::path& dir);

// Most points one sweep process may hold (its shard of the campaign): the journal's index keeps
// 16 bytes a point, reserved up front (1.6 GB at this size); larger campaigns run as shards.
inline constexpr std::uint64_t kMaxShardPoints = 100'000'000;

// What a caller may watch while run_sweep works on another thread (the Python module's progress
// bar): the shard's points, and those finished so far (run now, or found in the store).
struct SweepCounters {
  std::atomic<std::uint64_t> total{0}, finished{0};
};

struct SweepOptions {
  int threads = 0;  // 0: all hardware threads
  io::Shard shard;  // default 0/1: every point
  // How the points are dealt to shards (shard_plan.hpp). Empty: the store's own (provenance.yaml
  // shard_balance; a store written before it was recorded: index), cost for a new store.
  std::optional<ShardBalance> balance;
  std::filesystem::path out;  // empty: results/<campaign name>
  bool quiet = false;         // no progress, no summary
  bool retry_failed = false;  // rerun points the store holds as failed
  std::string command_line;   // the command that started the store (provenance.yaml)
  // Group commit of the journal (store.hpp): fdatasync after 100 points or 1 s, whichever comes
  // first, and at the end. A power cut loses (and the next run recomputes) at most the points
  // journaled in the last second, never more than 99; kill -9 loses none. {1, 0}: per point.
  JournalSync sync{100, 1.0};
  // The code that computes point hashes. A finished run records, in DIR/inputs.txt, this id,
  // the campaign's `set` (with --set) and the FNV-1a 64 of every file its points' hashes depend
  // on; the next run trusts the journal's index → hash when all of them are unchanged (no point is
  // rebuilt or re-hashed) and checks every stored point (in parallel) otherwise. Empty: never
  // trust (the default for a build whose git commit is unknown or dirty: its code may differ from
  // the commit's).
  std::string build_id = default_build_id();
  static std::string default_build_id();
  // Cooperative cancel (the Python module's Ctrl-C; the command line is ended by the signal
  // itself): once *stop is true, run_sweep syncs the journal, which keeps every point finished
  // so far, and throws RunInterrupted (observe/run_monitor.hpp); a rerun resumes. May be null.
  const std::atomic<bool>* stop = nullptr;
  SweepCounters* counters = nullptr;  // may be null
};

struct SweepReport {
  std::filesystem::path store;
  std::uint64_t points = 0;  // points of this shard
  ShardBalance balance = ShardBalance::index;
  // Expected seconds on one core (solve/core/run_cost.hpp) of this shard and of the costliest and
  // cheapest shard; NaN unless the plan was balanced by cost over unequal costs.
  double expected_s = std::numeric_limits<double>::quiet_NaN();
  double expected_max_s = std::numeric_limits<double>::quiet_NaN(), expected_min_s = expected_max_s;
  std::uint64_t skipped = 0;         // already in the store (same scene hash)
  std::uint64_t changed = 0;         // in the store with another hash (scene or data changed): rerun
  std::uint64_t ran = 0;             // run now
  std::uint64_t failed_now = 0;      // of those, failed
  std::uint64_t ok = 0, failed = 0;  // rows of this shard in the store at the end
  std::size_t dropped_lines = 0;     // torn/corrupt journal lines found at start
  bool trusted = false;              // stored hashes trusted (inputs.txt unchanged): none re-hashed
  std::uint64_t rehashed = 0;        // stored points whose scene was rebuilt and hashed
  std::uint64_t syncs = 0;           // fdatasync calls of the journal (group commits)
  double wall_s = 0;
};

// Throws RunInterrupted when SweepOptions::stop cut the sweep short.
SweepReport run_sweep(const Campaign& campaign, const SweepOptions& options);

// The points.csv header of a campaign: index, hash, experiment, every varied key, status, error,
// every observable, the solver statistics and wall_s.
std::string store_header(const Campaign& campaign);

// FNV-1a 64 of the bytes of data files, each read once per instance (one per sweep): a path's
// size and mtime do not prove its contents unchanged, its bytes do. Also notes the scene and
// experiment files the hashed scenes were read from (inputs(): every file a point's hash depends
// on). Thread-safe.
class FileHashes {
 public:
  std::uint64_t of(const std::filesystem::path& file);  // std::runtime_error when unreadable
  void note(const std::filesystem::path& file);         // a file read into the scene text
  // Every file given to of() or note(), absolute and normalised, sorted.
  std::vector<std::filesystem::path> inputs() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::uint64_t> by_path_;
  std::set<std::string> noted_;
};

// The text the point hash is taken of: scene_to_yaml with the experiment file written relative
// to `base_dir` (the campaign's folder), so the hash does not depend on where the project lives,
// followed by the hashes of the bytes of the junctions and measured CSVs: a point whose data
// changed has another hash, so a resume recomputes it and merge refuses to mix it.
std::string canonical_scene_text(const Scene& scene, const std::filesystem::path& base_dir, FileHashes& data);

}  // namespace asperity
