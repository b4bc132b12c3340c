#include "campaign/sweep.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "batch/inputs_fingerprint.hpp"
#include "batch/parallel_runner.hpp"
#include "batch/stop_flag.hpp"
#include "campaign/campaign_scenes.hpp"
#include "campaign/store.hpp"
#include "campaign/sweep_store_provenance.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/hash.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/progress.hpp"
#include "io/temp_files.hpp"
#include "observe/series_csv.hpp"
#include "observe/simulate.hpp"

namespace asperity {
namespace fs = std::filesystem;

using namespace sweep_detail;

namespace {

struct Job {
  Point point;
  std::optional<Scene> scene;
  std::uint64_t hash = 0;
  std::vector<std::string> varied;  // text of each varied key (store_header order)
  std::string error;                // non-empty: failed
  std::string row;
  bool failed = false;
  bool interrupted = false;  // stopped by SweepOptions::stop: no row (it reruns next time)
  bool has_series = false;   // series_rows is this point's block for series.csv
  std::string series_rows;   // "index,sample...\n" lines
};

// The sweep's counts (finished, skipped as already stored, failed) behind the one progress line
// of io/progress.hpp (redrawn on a terminal, a plain line every 10 s in a log).
class Progress {
 public:
  Progress(std::uint64_t total, bool quiet, SweepCounters* counters)
      : total_(total),
        skipped_(0),
        counters_(counters),
        line_("sweep", "points", static_cast<double>(total), quiet, 0.0, 10.0) {
    if (counters_) counters_->total = total;
  }

  void point_done(bool failed) {
    ++done_;
    if (counters_) ++counters_->finished;
    failed_ += failed ? 1 : 0;
    const std::uint64_t finished = std::min(total_, done_ + skipped_.load());
    line_.update(static_cast<double>(finished), std::to_string(failed_) + " failed");
  }
  void finish() { line_.close(); }
  // A point found in the store with its current hash (counted by the build stage, which runs
  // ahead of the writer: a stale stored point is not counted as finished).
  void skipped_one() {
    ++skipped_;
    if (counters_) ++counters_->finished;
  }

 private:
  std::uint64_t total_;
  std::atomic<std::uint64_t> skipped_;  // incremented by the build stage while the writer reads it
  std::uint64_t done_ = 0, failed_ = 0;
  SweepCounters* counters_;
  io::ProgressLine line_;
};

}  // namespace

std::string store_header(const Campaign& c) {
  std::string h = "index,hash,grid,experiment";
  for (const std::string& k : c.varied_keys()) h.append(",").append(io::csv_field(k));
  h += ",status,error";
  for (const ObservableField& f : observable_fields())
    if (f.per_point) h += std::string(",") + f.name;
  return h + ",wall_s";
}

namespace {

// One process holds an index entry per point of its shard (16 bytes, reserved up front): a
// shard larger than this is refused before anything is created, whatever the campaign's size.
void check_shard_size(const Campaign& c, const io::Shard& shard) {
  if (const std::uint64_t mine = shard.size(c.size()); mine > kMaxShardPoints)
    throw io::InputError("", 0, "--shard",
                         "this shard has " + std::to_string(mine) + " of the campaign's " + std::to_string(c.size()) +
                             " points, more than the " + std::to_string(kMaxShardPoints) +
                             " one process may hold; run it as at least " +
                             std::to_string((c.size() + kMaxShardPoints - 1) / kMaxShardPoints) + " shards");
}

// The shard's plan, its size and expected costs noted in the report.
ShardPlan plan_and_report(const Campaign& c, const io::Shard& shard, SweepReport& rep) {
  const ShardPlan plan = [&] {
    try {
      return plan_shard(c, shard, rep.balance);
    } catch (const std::invalid_argument& e) {  // --balance cost on too large a campaign: bad input
      throw io::InputError("", 0, "--balance", e.what());
    }
  }();
  rep.points = plan.size();
  if (!plan.expected_s().empty()) {
    const auto& e = plan.expected_s();
    rep.expected_s = e[shard.index];
    rep.expected_max_s = *std::max_element(e.begin(), e.end());
    rep.expected_min_s = *std::min_element(e.begin(), e.end());
  }
  return plan;
}

// Series: one append-only file (store.hpp, SeriesFile), its columns those of the shard's first
// point (every point's block has them), synced before the journal so that a synced row implies
// its synced series. Null for a campaign without series.
std::unique_ptr<SeriesFile> open_series(const Campaign& c, const fs::path& dir, const ShardPlan& shard,
                                        Journal& journal) {
  if (!c.series) return nullptr;
  std::vector<std::string> columns;
  if (!fs::exists(dir / "series.csv")) {
    try {
      columns = CampaignScenes(c).scene(point_at(c, shard.next(0))).output.series;
    } catch (const std::exception&) {  // no first point or an invalid one: every column
    }
    if (columns.empty()) columns = all_series();
  }
  auto series = std::make_unique<SeriesFile>(dir, true, columns);
  journal.before_sync([s = series.get()] { s->sync(); });
  return series;
}

// The text of each varied key at a point (store_header order): its axis value, or the scene's.
std::vector<std::string> varied_texts(const Point& p, const std::optional<Scene>& scene,
                                      const std::vector<std::string>& keys) {
  std::vector<std::string> out;
  for (const std::string& k : keys) {
    std::string v;
    bool mine = false;
    for (const PointValue& pv : p.values)
      if (pv.axis->key == k) v = pv.value.text, mine = true;
    if (!mine && scene) v = CampaignScenes::value_text(*scene, k);
    out.push_back(v);
  }
  return out;
}

// A run's series as a series.csv block's rows ("index,sample...\n" lines).
std::string series_block_rows(std::uint64_t index, const RunResult& r, const std::vector<std::string>& columns) {
  std::ostringstream csv;
  write_series_csv(csv, r.recorder.series(), columns);
  const std::string text = csv.str();
  const std::string prefix = std::to_string(index) + ",";
  std::string rows;
  rows.reserve(text.size() + r.recorder.series().size() * prefix.size());
  for (std::size_t at = text.find('\n') + 1; at < text.size();) {  // past the header
    const std::size_t nl = text.find('\n', at);
    rows.append(prefix).append(text, at, nl + 1 - at);
    at = nl + 1;
  }
  return rows;
}

// Why a finished run counts as failed (empty: it did not).
std::string run_failure(const Campaign& c, const RunResult& r) {
  if (r.recorder.timed_out())
    return "per-point time limit of " + io::format_exact(c.time_limit_s) +
           " s exceeded at simulated t = " + io::format_exact(r.recorder.last().t) + " s";
  // A run that ends before any junction slips has no peak (Q_s = NaN) and is not a failure.
  const bool peak = r.obs.peak_found;
  for (const auto& [name, x] : {std::pair<const char*, double>{"Q_s", peak ? r.obs.Q_s : 0.0},
                                {"A_s", peak ? r.obs.A_s : 0.0},
                                {"t_peak", peak ? r.obs.t_peak : 0.0},
                                {"t_end", r.obs.t_end}})
    if (!std::isfinite(x)) return std::string("non-finite observable ") + name;
  return {};
}

// The journal row of a job: index, hash, grid, experiment, varied values, status, error,
// observables (empty when failed), wall time.
std::string job_row(const Campaign& c, const Job& job, const std::optional<RunResult>& r, double wall) {
  std::string row = std::to_string(job.point.index) + "," + io::hex16(job.hash) + "," +
                    io::csv_field(c.grids[job.point.grid].name) + "," +
                    io::csv_field(job.scene ? job.scene->experiment.name : "");
  for (const std::string& v : job.varied) row.append(",").append(io::csv_field(v));
  row += job.failed ? ",failed," + io::csv_field(job.error) : ",ok,";
  for (const ObservableField& f : observable_fields())
    if (f.per_point)
      row.append(",").append(r && !job.failed ? observable_text(f, r->obs, io::format_exact) : std::string());
  return row + "," + io::format_exact(wall);
}

// The three stages of the sweep's pipeline over one shard (sweep.hpp) and what they share.
class ShardRun {
 public:
  ShardRun(const Campaign& c, const SweepOptions& opt, const ShardPlan& shard, Journal& journal, SeriesFile* series,
           std::vector<std::uint8_t> current, FileHashes& data_hashes, SweepReport& rep)
      : c_(c),
        opt_(opt),
        shard_(shard),
        journal_(journal),
        series_(series),
        stored_(journal.entries()),
        current_(std::move(current)),
        data_hashes_(data_hashes),
        rep_(rep),
        scenes_(c),
        varied_keys_(c.varied_keys()),
        series_columns_(series ? series->columns() : std::vector<std::string>{}),
        progress_(rep.points, opt.quiet, opt.counters),
        stop_(opt.stop),
        next_(shard.next(0)) {}

  // Serial, in order: the next point of the shard that needs a run; null at the end or on a stop.
  std::shared_ptr<Job> build() {
    while (next_ < c_.size()) {
      if (stop_.requested()) {
        cut_short_ = true;
        break;
      }
      const std::uint64_t index = next_;
      next_ = shard_.next(index + 1);
      if (auto job = job_for(index)) return job;
    }
    return nullptr;
  }

  // Parallel: runs the job's scene and formats its row (and series block).
  void run(Job& job) {
    omp_set_num_threads(1);  // see sweep.hpp: the points are the parallelism
    std::optional<RunResult> r;
    double wall = 0;
    if (job.scene) {
      const auto t = std::chrono::steady_clock::now();
      try {
        r = simulate(*job.scene, c_.time_limit_s, stop_.monitor());
        job.error = run_failure(c_, *r);
        if (series_ && job.error.empty()) {  // the block's rows, formatted here in parallel
          job.series_rows = series_block_rows(job.point.index, *r, series_columns_);
          job.has_series = true;
        }
      } catch (const RunInterrupted&) {
        job.interrupted = true;
        cut_short_ = true;
        return;
      } catch (const SolverError& e) {
        job.error = std::string("solver error: ") + e.what();
      } catch (const std::exception& e) {
        job.error = e.what();
      }
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    }
    job.failed = !job.error.empty();
    job.row = job_row(c_, job, r, wall);
    job.scene.reset();  // free the junctions before the job waits for the writer
  }

  // Serial, out of order: the job's series block, then its row.
  void store(Job& job) {
    if (job.interrupted) return;
    if (job.has_series) series_->append(job.point.index, job.hash, job.series_rows);  // before its row
    journal_.append(job.row);
    ++rep_.ran;
    rep_.failed_now += job.failed ? 1 : 0;
    progress_.point_done(job.failed);
  }
  void finish() { progress_.finish(); }

  bool cut_short() const { return cut_short_; }  // the stop left points of the shard unrun

 private:
  // A stored ok point of a series campaign counts only with its series block (same scene hash):
  // a power cut may keep a journal row whose block was lost.
  bool has_series(const StoredRow& st) const {
    if (!series_ || !st.ok()) return true;
    const SeriesBlock* b = series_->find(st.index);
    return b && b->hash == row_hash(journal_.row(st));
  }
  bool keep(const StoredRow& st) const { return (st.ok() || !opt_.retry_failed) && has_series(st); }

  // The job of point `index`; null when the store holds it already (counted as skipped).
  std::shared_ptr<Job> job_for(std::uint64_t index) {
    while (cursor_ < stored_.size() && stored_[cursor_].index < index) ++cursor_;
    const StoredRow* st = cursor_ < stored_.size() && stored_[cursor_].index == index ? &stored_[cursor_] : nullptr;
    if (st && current_[cursor_] && keep(*st)) return skip();
    auto job = std::make_shared<Job>();
    job->point = point_at(c_, index);
    try {
      job->scene = scenes_.scene(job->point);
      job->hash = io::fnv1a64(canonical_scene_text(*job->scene, c_.file.parent_path(), data_hashes_));
    } catch (const std::exception& e) {  // a bad combination of values: recorded, not fatal
      job->scene.reset();
      job->error = e.what();
      job->hash = io::fnv1a64("invalid point: " + job->error);
    }
    if (st) {
      const bool same = row_hash(journal_.row(*st)) == job->hash;  // pread of an old row: safe while the writer appends
      if (same && keep(*st)) return skip();
      // Stored from another scene or other data: rerun; the new row supersedes the stale one.
      if (!same) ++rep_.changed;
    }
    job->varied = varied_texts(job->point, job->scene, varied_keys_);
    return job;
  }
  std::shared_ptr<Job> skip() {
    ++rep_.skipped;
    progress_.skipped_one();
    return nullptr;
  }

  const Campaign& c_;
  const SweepOptions& opt_;
  const ShardPlan& shard_;
  Journal& journal_;
  SeriesFile* series_;
  const std::span<const StoredRow> stored_;  // the journal at the start, ascending by index
  const std::vector<std::uint8_t> current_;  // per stored row: its hash is the one its point gives now
  FileHashes& data_hashes_;
  SweepReport& rep_;
  CampaignScenes scenes_;
  const std::vector<std::string> varied_keys_, series_columns_;
  Progress progress_;
  const StopFlag stop_;  // points in flight poll it: a Ctrl-C ends the sweep well within a second
  std::uint64_t next_;
  std::size_t cursor_ = 0;  // into stored_, which is ascending like the points built
  std::atomic<bool> cut_short_{false};
};

}  // namespace

SweepReport run_sweep(const Campaign& c, const SweepOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  SweepReport rep;
  rep.store = opt.out.empty() ? fs::path("results") / c.name : opt.out;
  check_store_folder(rep.store);
  check_shard_size(c, opt.shard);
  fs::create_directories(rep.store);
  StoreLock lock(rep.store);
  io::remove_stale_temporaries(rep.store);  // of a sweep or merge that died while writing (kill -9, a lost node)
  rep.balance = prepare_store(rep.store, c, opt);
  const ShardPlan shard = plan_and_report(c, opt.shard, rep);
  // Room for one row per point of the shard: the index the build stage reads (entries()) does
  // not move while the writer stage appends (each point is appended at most once per run).
  Journal journal(rep.store, store_header(c), opt.sync, rep.points);
  rep.dropped_lines = journal.dropped_lines();
  const std::unique_ptr<SeriesFile> series = open_series(c, rep.store, shard, journal);
  FileHashes data_hashes;  // thread-safe: the check of stored points hashes in parallel
  data_hashes.note(c.file);
  const ParallelRunner runner(opt.threads);

  // Are the stored hashes still the ones the points' scenes and data give? Trusted when the
  // inputs the last complete run checked them against are unchanged; otherwise every stored point
  // is checked. inputs.txt is removed before anything is appended: a run killed after running
  // points with other files leaves none, and the next run checks everything.
  std::string points_digest;  // SHA-256 of points.csv as the last complete run wrote it
  if (std::optional<std::string> old = read_inputs(rep.store)) {
    points_digest = take_points_digest(*old);
    rep.trusted =
        !opt.build_id.empty() && inputs_text(c, opt.build_id, shard, listed_inputs(*old, c), data_hashes) == *old;
    io::remove_file_durably(rep.store / kInputsFileName);
  }
  std::vector<std::uint8_t> current(journal.entries().size(), 1);
  if (!rep.trusted) current = recheck_stored(c, opt, shard, journal, data_hashes, runner, rep.rehashed);

  ShardRun stages(c, opt, shard, journal, series.get(), std::move(current), data_hashes, rep);
  runner.pipeline<Job>([&] { return stages.build(); }, [&](Job& j) { stages.run(j); },
                       [&](Job& j) { stages.store(j); });
  stages.finish();
  journal.sync();
  rep.syncs = journal.syncs();
  // Stopped: the journal (synced above) keeps what ran; points.csv and inputs.txt are written by
  // the run that completes the shard (inputs.txt is absent now, so it checks every stored point).
  if (stages.cut_short())
    throw RunInterrupted("interrupted; " + std::to_string(rep.skipped + rep.ran) + " of " + std::to_string(rep.points) +
                         " point(s) of this shard kept in " + rep.store.string() + " (" + std::to_string(rep.ran) +
                         " run now); rerun the same command to resume");

  auto mine = [&](std::uint64_t index) { return index < c.size() && shard.contains(index); };
  const bool unchanged = points_current(rep, points_digest);
  journal.settle();
  if (!unchanged) points_digest = journal.write_points(rep.store, mine);
  if (series) compact_series(*series, journal);
  // Every stored point of the shard is now checked against (or computed from) these inputs.
  if (!opt.build_id.empty())
    write_inputs(rep.store, inputs_text(c, opt.build_id, shard, data_hashes.inputs(), data_hashes) + kPointsDigestTag +
                                points_digest + "\n");
  for (const StoredRow& e : journal.entries())
    if (mine(e.index)) (e.ok() ? rep.ok : rep.failed) += 1;
  rep.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return rep;
}

}  // namespace asperity
