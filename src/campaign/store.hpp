#pragma once
// The result store of a campaign, a folder (results/<campaign>/ by default):
//   journal.csv     append-only, the truth: a header, then one line per finished point, each
//                   line = the points.csv row + "," + SHA-256 of that row (io/journal_line.hpp;
//                   journals from before it carry FNV-1a 64 and are rewritten when appended to).
//                   Appended with one write() per point by one thread, so after kill -9 at any
//                   instant the file is good lines followed by at most one torn last line,
//                   which the checksum detects and the next run drops (and recomputes).
//                   fdatasync() runs once per group of points (JournalSync): a power cut or
//                   kernel crash may lose the lines written since the last one (those points
//                   rerun), or leave garbage in their place, which the checksum drops.
//   points.csv      the rows of the journal sorted by point index, one per point (latest wins),
//                   written atomically (temp + rename) at the end of every run and by merge.
//   provenance.yaml campaign file and its hash, project version, build type, date: written once.
//   campaign.yaml   a copy of the campaign file as it was when the store was started.
//   series.csv      optional series of every point, one block per point (campaign `series: true`;
//                   SeriesFile below). Stores written before it hold series/HASH.csv per point.
//   .lock           flock: one sweep per store at a time.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

// The store is written with these (its users call them through this header too).
#include "batch/journal_file.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/dir_lock.hpp"
#include "io/hash.hpp"
#include "io/journal_line.hpp"

namespace asperity {

// One stored row in an index, 16 bytes whatever the row holds (a store of 10^7 points indexes in
// 160 MB): the point index, where the row's line starts in the store file, whether its status is
// ok. The row's text stays in the file and is read back by offset (up to its newline).
struct StoredRow {
  std::uint64_t index = 0;
  std::uint64_t at = 0;  // offset << 1 | ok
  std::uint64_t offset() const { return at >> 1; }
  bool ok() const { return (at & 1) != 0; }
};

// Rows of a store file by point index: a vector of StoredRow sorted by index, one per index (the
// row written last, i.e. at the largest offset, wins). Rows are added in file order and sorted
// in place by settle(), so no node per row (a std::map cost ~80 bytes per point) and no second
// copy while sorting.
class RowIndex {
 public:
  void reserve(std::size_t n) { v_.reserve(n); }
  std::size_t capacity() const { return v_.capacity(); }
  void add(std::uint64_t index, std::uint64_t offset, bool ok) { v_.push_back({index, offset << 1 | (ok ? 1u : 0u)}); }
  // Sorts what was added since the last settle() in with the rest; the last row of an index wins.
  void settle();
  // The settled rows, ascending by index (rows added since the last settle() not included).
  std::span<const StoredRow> rows() const { return {v_.data(), settled_}; }
  const StoredRow* find(std::uint64_t index) const;  // in rows(); nullptr when absent
  void clear() { v_.clear(), settled_ = 0; }

 private:
  std::vector<StoredRow> v_;
  std::size_t settled_ = 0;
};

// When the journal is made durable (fdatasync): after `every` points appended since the last
// sync, or at the first append `seconds` or more after the last sync, and by sync() (the sweep
// calls it at its end) and the destructor. Lines are written at once either way (kill -9 loses
// none); only a power cut or a kernel crash can lose the unsynced ones: at most every − 1
// points, all journaled within `seconds` of the last append before the cut.
struct JournalSync {
  std::uint32_t every = 1;  // 1: fdatasync per point
  double seconds = 0;       // 0: no time bound (only `every`)
};

// Opens (creating when absent) DIR/journal.csv for appending, after recovering it: lines with a
// bad checksum and a torn last line are dropped (the file is rewritten atomically without them).
// A store holding points.csv but no journal (a committed store) is seeded from points.csv.
// A header different from `header` (another campaign or version) → std::runtime_error.
class Journal {
 public:
  // `room`: the most rows this Journal object will append. Capacity for them is reserved up
  // front (virtual memory: a page costs only once written), so appending them never moves the
  // index and entries() taken before stays valid while the writer appends (the sweep's build
  // stage reads it while its writer stage appends).
  Journal(const std::filesystem::path& dir, const std::string& header, JournalSync sync = {}, std::uint64_t room = 0);
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  std::size_t dropped_lines() const { return dropped_; }  // found torn or corrupt at open
  // The rows by index (latest wins) as of the open or the last write_points()/settle(); rows
  // appended since are added by settle().
  std::span<const StoredRow> entries() const { return index_.rows(); }
  const StoredRow* find(std::uint64_t index) const { return index_.find(index); }
  void settle() { index_.settle(); }

  // Appends one row (no newline; first field the index, second the hash in hex, a `status`
  // column as in the header): write(), then fdatasync() when the JournalSync says so. Not
  // thread-safe: one writer, and entries() must not be read concurrently.
  void append(const std::string& row);

  // fdatasync() of the rows appended since the last one (none: nothing to do), after calling the
  // hook set here (the sweep syncs series.csv first: a synced row implies its synced series).
  void sync();
  void before_sync(std::function<void()> hook) { before_sync_ = std::move(hook); }
  std::uint64_t syncs() const { return syncs_; }  // fdatasync calls so far

  // The row text of an entry (thread-safe: pread).
  std::string row(const StoredRow& e) const;

  // settle(), then writes DIR/points.csv atomically, streamed (each row read back from the
  // journal in index order; memory does not grow with the rows): header + rows of the entries
  // whose index `keep(index)`. Returns the SHA-256 of the bytes written.
  std::string write_points(const std::filesystem::path& dir, const std::function<bool(std::uint64_t)>& keep);

  static std::size_t status_column(const std::string& header);

 private:
  bool scan(const std::filesystem::path& path);
  void add_entry(std::string_view row, std::uint64_t offset);
  std::string header_;
  io::JournalDigest digest_ = io::JournalDigest::sha256;  // of the journal as read (legacy: rewritten at open)
  std::size_t status_col_;
  std::unique_ptr<JournalFile> file_;  // open once the journal is recovered
  std::uint64_t size_ = 0;
  std::size_t dropped_ = 0;
  JournalSync policy_;
  std::uint32_t unsynced_ = 0;  // rows appended since the last fdatasync
  std::uint64_t syncs_ = 0;
  std::chrono::steady_clock::time_point last_sync_;
  RowIndex index_;
  std::function<void()> before_sync_;
};

// The rows of a store, read-only (merge, plot, tests): the journal's valid rows (torn and corrupt
// lines skipped, the latest row of an index wins), or the rows of points.csv when the store has
// no journal (e.g. a committed one). Only the index (16 bytes per row: StoredRow) is held; each
// row's text is read when asked for, so memory does not grow with the rows' text. ok() of its
// entries is not set (a reader has no use for it).
class StoreReader {
 public:
  explicit StoreReader(const std::filesystem::path& dir);  // std::runtime_error: not a store
  ~StoreReader();
  StoreReader(StoreReader&& o) noexcept;
  StoreReader(const StoreReader&) = delete;
  StoreReader& operator=(const StoreReader&) = delete;
  StoreReader& operator=(StoreReader&&) = delete;

  const std::string& header() const { return header_; }             // the points.csv header
  std::span<const StoredRow> rows() const { return rows_.rows(); }  // ascending by index
  std::string row(const StoredRow& r) const;

 private:
  std::filesystem::path file_;
  std::string header_;
  RowIndex rows_;
  bool journal_ = false;  // lines end with ",checksum"
  int fd_ = -1;
};

// DIR/series.csv (campaign `series: true`): the sampled series of every point of the store in
// one append-only file, a block per point, appended by the sweep's writer stage:
//   index,t,Q,A                     header: "index", then the series columns (those of the first
//                                   point of the store's shard, output.series; every block has them)
//   7,0,0,0                         the block's rows: the point's index, then one sample
//   7,0.001,0.52,1.1e-06
//   #end,7,HASH,2,CHECKSUM          trailer: index, scene hash, rows, FNV-1a 64 of the rows' bytes
// A block counts only whole (trailer present, checksum matching): after kill -9 during a write
// the file is good blocks plus at most one torn one, which the next sweep cuts off (the point
// reruns: its block is written, and synced, before its journal row). The last block of an index
// wins; at the end of a run the file is rewritten without superseded blocks when it holds any, so
// a finished store's series.csv reads as one CSV: pandas.read_csv(".../series.csv", comment="#").
struct SeriesBlock {
  std::uint64_t index = 0, hash = 0;
  std::uint64_t offset = 0, end = 0;  // the rows' bytes [offset, end) (the trailer starts at end)
};

// A block as series.csv holds it: `rows` (whole lines) and their trailer.
std::string series_block(std::uint64_t index, std::uint64_t hash, const std::string& rows);

class SeriesFile {
 public:
  // Opens DIR/series.csv for reading (append = false) or, creating it with `columns` when absent
  // and cutting off a torn or corrupt tail, for appending. A header other than "index" + columns
  // (when columns are given) → std::runtime_error.
  SeriesFile(const std::filesystem::path& dir, bool append, const std::vector<std::string>& columns = {});
  ~SeriesFile();
  SeriesFile(const SeriesFile&) = delete;
  SeriesFile& operator=(const SeriesFile&) = delete;

  const std::vector<std::string>& columns() const { return columns_; }  // without "index"
  std::size_t dropped_bytes() const { return dropped_; }                // cut off at open
  // The last whole block of `index` as of the open (nullptr: none).
  const SeriesBlock* find(std::uint64_t index) const;
  bool superseded() const { return superseded_; }  // an index with more than one block (as opened or appended)
  const std::vector<SeriesBlock>& blocks() const { return blocks_; }  // the last of each index, as opened
  // The rows of a block ("index,value,...\n" lines) (thread-safe: pread).
  std::string rows(const SeriesBlock& b) const;

  // Appends one block: `rows` are whole lines, each starting with the index. Not thread-safe.
  void append(std::uint64_t index, std::uint64_t hash, const std::string& rows);
  void sync();  // fdatasync when anything was appended since the last one
  // Rewrites the file atomically with only the last block of each index for which
  // keep(index, hash) holds (streamed: the blocks are copied by offset).
  void compact(const std::function<bool(std::uint64_t, std::uint64_t)>& keep);

 private:
  std::filesystem::path path_;
  std::string header_;
  std::vector<std::string> columns_;
  std::vector<SeriesBlock> blocks_;      // sorted by index (last block of each), as opened
  std::vector<std::uint64_t> appended_;  // indices appended since the open
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::size_t dropped_ = 0;
  bool superseded_ = false, unsynced_ = false;
};

// The series of stored points as CSV text (a header of the series columns, then one row per
// sample, without the index column), by point index: from DIR/series.csv, the block whose scene
// hash is that of the point's row, or, in a store written before series.csv, series/HASH.csv.
// Points without series (not stored, failed, a campaign without `series: true`) are absent.
std::map<std::uint64_t, std::string> read_point_series(const std::filesystem::path& dir,
                                                       const std::vector<std::uint64_t>& indices);

// An exclusive lock on DIR/.lock held for the object's lifetime (std::runtime_error "another sweep
// is writing DIR ..." when another process holds it).
class StoreLock : public io::DirLock {
 public:
  explicit StoreLock(const std::filesystem::path& dir) : io::DirLock(dir, "sweep") {}
};

}  // namespace asperity
