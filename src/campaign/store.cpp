#include "campaign/store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
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

}  // namespace

std::size_t Journal::status_column(const std::string& header) {
  const auto cols = csv_split(header);
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (cols[i] == "status") return i;
  throw std::runtime_error("store header has no status column");
}

void Journal::add_entry(const std::string& row, std::uint64_t offset) {
  const auto f = csv_split(row);
  std::uint64_t index = 0, hash = 0;
  if (f.size() <= status_col_ || !parse_u64(f[0], index) || !parse_u64(f[1], hash, 16))
    throw std::runtime_error("malformed journal row (checksum good): " + row.substr(0, 60));
  entries_[index] = JournalEntry{hash, f[status_col_] == "ok", offset, static_cast<std::uint32_t>(row.size())};
}

Journal::Journal(const fs::path& dir, const std::string& header, JournalSync sync)
    : header_(header), status_col_(status_column(header)), policy_(sync), last_sync_(std::chrono::steady_clock::now()) {
  if (policy_.every == 0) policy_.every = 1;
  const fs::path path = dir / "journal.csv";
  std::string good = header_ + ",check\n";
  if (!fs::exists(path) && fs::exists(dir / "points.csv")) {
    // A store without its journal (e.g. a committed one: only points.csv is kept in git).
    // points.csv is only ever written atomically, so its rows seed the journal as they are.
    const std::string text = read_file_text(dir / "points.csv");
    const std::size_t nl = text.find('\n');
    if (nl == std::string::npos || text.compare(0, nl, header_) != 0)
      throw std::runtime_error((dir / "points.csv").string() + " was written for another campaign or version "
                               "(header differs); use another --out or remove the store");
    for (std::size_t pos = nl + 1; pos < text.size();) {
      const std::size_t end = text.find('\n', pos);
      if (end == std::string::npos) break;
      const std::string_view row(text.data() + pos, end - pos);
      good.append(row).append(",").append(hex16(fnv1a64(row))).append("\n");
      pos = end + 1;
    }
  } else if (fs::exists(path)) {
    const std::string text = read_file_text(path);
    std::size_t pos = 0;
    bool header_seen = false;
    std::string rebuilt;
    while (pos < text.size()) {
      const std::size_t nl = text.find('\n', pos);
      if (nl == std::string::npos) {  // torn last line (no newline): drop it
        ++dropped_;
        break;
      }
      const std::string_view line(text.data() + pos, nl - pos);
      pos = nl + 1;
      if (!header_seen) {
        if (line != header_ + ",check")
          throw std::runtime_error(path.string() + " was written for another campaign or version (header differs); "
                                   "use another --out or remove the store");
        header_seen = true;
        continue;
      }
      std::string_view row;
      if (!checked_row(line, row)) {
        ++dropped_;
        continue;
      }
      rebuilt.append(row).append(",").append(hex16(fnv1a64(row))).append("\n");
    }
    if (header_seen && dropped_ == 0) good.clear();  // intact: append to it as it is
    else good += rebuilt;
  }
  if (!good.empty()) write_file_durably(path, good);  // new, or recovered without the bad lines
  fd_ = ::open(path.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) sys_fail("cannot open", path);
  // Index the rows (offsets into the file as it is now).
  const std::string text = read_file_text(path);
  std::size_t pos = text.find('\n') + 1;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    std::string_view row;
    checked_row(std::string_view(text.data() + pos, nl - pos), row);
    add_entry(std::string(row), pos);
    pos = nl + 1;
  }
  size_ = text.size();
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

std::string Journal::row(const JournalEntry& e) const {
  std::string s(e.length, '\0');
  std::size_t got = 0;
  while (got < s.size()) {
    const ssize_t r = ::pread(fd_, s.data() + got, s.size() - got, static_cast<off_t>(e.offset + got));
    if (r <= 0) {
      if (r < 0 && errno == EINTR) continue;
      throw std::runtime_error("cannot read journal.csv");
    }
    got += static_cast<std::size_t>(r);
  }
  return s;
}

void Journal::write_points_impl(const fs::path& dir, const std::vector<const JournalEntry*>& rows) const {
  std::string text = header_ + "\n";
  for (const JournalEntry* e : rows) text += row(*e) + "\n";
  write_file_durably(dir / "points.csv", text);
}

StoreRows read_store(const fs::path& dir) {
  const fs::path path = dir / "journal.csv";
  if (!fs::exists(path)) {  // a store without its journal (e.g. committed): its points.csv
    if (!fs::exists(dir / "points.csv"))
      throw std::runtime_error("not a sweep store (no journal.csv or points.csv): " + dir.string());
    const std::string text = read_file_text(dir / "points.csv");
    StoreRows s;
    std::size_t pos = text.find('\n');
    if (pos == std::string::npos) throw std::runtime_error("empty " + (dir / "points.csv").string());
    s.header = text.substr(0, pos);
    for (++pos; pos < text.size();) {
      const std::size_t nl = text.find('\n', pos);
      if (nl == std::string::npos) break;
      const std::string row = text.substr(pos, nl - pos);
      std::uint64_t index = 0;
      if (parse_u64(std::string_view(row).substr(0, row.find(',')), index)) s.rows[index] = row;
      pos = nl + 1;
    }
    return s;
  }
  const std::string text = read_file_text(path);
  StoreRows s;
  std::size_t pos = text.find('\n');
  if (pos == std::string::npos) throw std::runtime_error("empty journal: " + path.string());
  s.header = text.substr(0, pos);
  const std::string suffix = ",check";
  if (s.header.size() < suffix.size() || s.header.compare(s.header.size() - suffix.size(), suffix.size(), suffix) != 0)
    throw std::runtime_error("malformed journal header: " + path.string());
  s.header.resize(s.header.size() - suffix.size());
  ++pos;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) break;  // torn
    std::string_view row;
    if (checked_row(std::string_view(text.data() + pos, nl - pos), row)) {
      const std::size_t comma = row.find(',');
      std::uint64_t index = 0;
      if (comma != std::string_view::npos && parse_u64(row.substr(0, comma), index)) s.rows[index] = std::string(row);
    }
    pos = nl + 1;
  }
  return s;
}

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
