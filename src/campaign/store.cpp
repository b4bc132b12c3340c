#include "campaign/store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace asperity {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void sys_fail(const std::string& what, const fs::path& p) {
  throw std::runtime_error(what + " " + p.string() + ": " + std::strerror(errno));
}

bool parse_u64(std::string_view s, std::uint64_t& out, int base = 10) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out, base);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && !s.empty();
}

// A journal line "row,checksum" → row when the checksum matches.
bool checked_row(std::string_view line, std::string_view& row) {
  const std::size_t comma = line.rfind(',');
  if (comma == std::string_view::npos || line.size() - comma - 1 != 16) return false;
  std::uint64_t sum = 0;
  if (!parse_u64(line.substr(comma + 1), sum, 16)) return false;
  row = line.substr(0, comma);
  return fnv1a64(row) == sum;
}

// Reads a file line by line (buffered), with each line's byte offset; a last line without its
// newline is not returned (torn() says it was there).
class LineReader {
 public:
  explicit LineReader(const fs::path& path) : in_(path, std::ios::binary) {
    if (!in_) throw std::runtime_error("cannot open " + path.string());
  }
  bool next(std::string& line, std::uint64_t& offset) {
    offset = pos_;
    if (!std::getline(in_, line)) return false;
    if (in_.eof()) {  // no newline after it
      torn_ = true;
      return false;
    }
    pos_ += line.size() + 1;
    return true;
  }
  bool torn() const { return torn_; }
  std::uint64_t offset() const { return pos_; }  // bytes of the complete lines read

 private:
  std::ifstream in_;
  std::uint64_t pos_ = 0;
  bool torn_ = false;
};

std::string read_span(int fd, std::uint64_t offset, std::uint32_t length, const std::string& file) {
  std::string s(length, '\0');
  std::size_t got = 0;
  while (got < s.size()) {
    const ssize_t r = ::pread(fd, s.data() + got, s.size() - got, static_cast<off_t>(offset + got));
    if (r <= 0) {
      if (r < 0 && errno == EINTR) continue;
      throw std::runtime_error("cannot read " + file);
    }
    got += static_cast<std::size_t>(r);
  }
  return s;
}

}  // namespace

std::size_t Journal::status_column(const std::string& header) {
  const auto cols = csv_split(header);
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (cols[i] == "status") return i;
  throw std::runtime_error("store header has no status column");
}

void Journal::add_entry(std::string_view row, std::uint64_t offset) {
  const auto f = csv_split(std::string(row));
  std::uint64_t index = 0, hash = 0;
  if (f.size() <= status_col_ || !parse_u64(f[0], index) || !parse_u64(f[1], hash, 16))
    throw std::runtime_error("malformed journal row (checksum good): " + std::string(row.substr(0, 60)));
  entries_[index] = JournalEntry{hash, f[status_col_] == "ok", offset, static_cast<std::uint32_t>(row.size())};
}

// Indexes the rows of journal.csv, streamed; false when it holds lines to drop (a torn last line,
// bad checksums, no header), which are counted in dropped_.
bool Journal::scan(const fs::path& path) {
  entries_.clear();
  LineReader in(path);
  std::string line;
  std::uint64_t offset = 0;
  if (!in.next(line, offset)) {
    dropped_ += in.torn() ? 1 : 0;
    return false;
  }
  if (line != header_ + ",check")
    throw std::runtime_error(path.string() + " was written for another campaign or version (header differs); "
                             "use another --out or remove the store");
  bool clean = true;
  while (in.next(line, offset)) {
    std::string_view row;
    if (checked_row(line, row)) add_entry(row, offset);
    else ++dropped_, clean = false;
  }
  if (in.torn()) ++dropped_, clean = false;
  size_ = in.offset();
  return clean;
}

Journal::Journal(const fs::path& dir, const std::string& header, JournalSync sync)
    : header_(header), status_col_(status_column(header)), policy_(sync), last_sync_(std::chrono::steady_clock::now()) {
  if (policy_.every == 0) policy_.every = 1;
  const fs::path path = dir / "journal.csv";
  const std::string head = header_ + ",check\n";
  std::string line;
  std::uint64_t offset = 0;
  bool indexed = false;
  if (!fs::exists(path) && fs::exists(dir / "points.csv")) {
    // A store without its journal (e.g. a committed one: only points.csv is kept in git).
    // points.csv is only ever written atomically, so its rows seed the journal as they are.
    LineReader in(dir / "points.csv");
    if (!in.next(line, offset) || line != header_)
      throw std::runtime_error((dir / "points.csv").string() + " was written for another campaign or version "
                               "(header differs); use another --out or remove the store");
    AtomicFileWriter out(path, Durability::synced);
    out.write(head);
    while (in.next(line, offset)) out.write(line + "," + hex16(fnv1a64(line)) + "\n");
    out.commit();
  } else if (!fs::exists(path)) {
    write_file_durably(path, head);
  } else if (scan(path)) {
    indexed = true;  // intact: appended to as it is
  } else {
    // Recovered: rewritten atomically without the torn or corrupt lines (streamed).
    AtomicFileWriter out(path, Durability::synced);
    out.write(head);
    LineReader in(path);
    for (bool first = true; in.next(line, offset); first = false) {
      std::string_view row;
      if (!first && checked_row(line, row)) out.write(line + "\n");
    }
    out.commit();
  }
  fd_ = ::open(path.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) sys_fail("cannot open", path);
  if (!indexed) {  // the offsets into the file as it is now
    const std::size_t dropped = dropped_;
    scan(path);
    dropped_ = dropped;
  }
}

Journal::~Journal() {
  if (fd_ < 0) return;
  if (unsynced_ > 0) ::fdatasync(fd_);  // no throwing here: a failure leaves rows to rerun
  ::close(fd_);
}

void Journal::append(const std::string& row) {
  const std::string line = row + "," + hex16(fnv1a64(row)) + "\n";
  if (!write_fully(fd_, line)) sys_fail("cannot write", "journal.csv");
  add_entry(row, size_);
  size_ += line.size();
  ++unsynced_;
  if (unsynced_ >= policy_.every ||
      (policy_.seconds > 0 &&
       std::chrono::duration<double>(std::chrono::steady_clock::now() - last_sync_).count() >= policy_.seconds))
    sync();
}

void Journal::sync() {
  if (unsynced_ == 0) return;
  if (::fdatasync(fd_) != 0) sys_fail("cannot sync", "journal.csv");
  unsynced_ = 0;
  ++syncs_;
  last_sync_ = std::chrono::steady_clock::now();
}

std::string Journal::row(const JournalEntry& e) const { return read_span(fd_, e.offset, e.length, "journal.csv"); }

void Journal::write_points(const fs::path& dir, const std::function<bool(std::uint64_t)>& keep) const {
  AtomicFileWriter out(dir / "points.csv", Durability::synced);
  out.write(header_ + "\n");
  for (const auto& [index, e] : entries_)
    if (keep(index)) out.write(row(e) + "\n");
  out.commit();
}

StoreReader::StoreReader(const fs::path& dir) {
  file_ = dir / "journal.csv";
  const bool journal = fs::exists(file_);
  if (!journal) {  // a store without its journal (e.g. committed): its points.csv
    file_ = dir / "points.csv";
    if (!fs::exists(file_)) throw std::runtime_error("not a sweep store (no journal.csv or points.csv): " + dir.string());
  }
  LineReader in(file_);
  std::string line;
  std::uint64_t offset = 0;
  if (!in.next(line, offset)) throw std::runtime_error("empty " + file_.string());
  header_ = line;
  const std::string suffix = ",check";
  if (journal) {
    if (header_.size() < suffix.size() || header_.compare(header_.size() - suffix.size(), suffix.size(), suffix) != 0)
      throw std::runtime_error("malformed journal header: " + file_.string());
    header_.resize(header_.size() - suffix.size());
  }
  while (in.next(line, offset)) {
    std::string_view row = line;
    if (journal && !checked_row(line, row)) continue;
    const std::size_t comma = row.find(',');
    std::uint64_t index = 0;
    if (comma != std::string_view::npos && parse_u64(row.substr(0, comma), index))
      rows_[index] = RowSpan{offset, static_cast<std::uint32_t>(row.size())};
  }
  fd_ = ::open(file_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) sys_fail("cannot open", file_);
}

StoreReader::~StoreReader() {
  if (fd_ >= 0) ::close(fd_);
}

StoreReader::StoreReader(StoreReader&& o) noexcept
    : file_(std::move(o.file_)), header_(std::move(o.header_)), rows_(std::move(o.rows_)), fd_(o.fd_) {
  o.fd_ = -1;
}

std::string StoreReader::row(const RowSpan& r) const { return read_span(fd_, r.offset, r.length, file_.string()); }

StoreLock::StoreLock(const fs::path& dir) {
  const fs::path p = dir / ".lock";
  fd_ = ::open(p.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) sys_fail("cannot open", p);
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
    throw std::runtime_error("another sweep is writing " + dir.string() + " (" + p.string() + " is locked)");
  }
}

StoreLock::~StoreLock() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace asperity
