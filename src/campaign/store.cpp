#include "campaign/store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "batch/journal_file.hpp"
#include "io/digest.hpp"
#include "io/input_error.hpp"
#include "io/journal_line.hpp"
#include "io/safe_open.hpp"

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

// Reads a file line by line (buffered), with each line's byte offset; a last line without its
// newline is not returned (torn() says it was there).
class LineReader {
 public:
  // Opened without following a link, a regular file only (io/safe_open.hpp).
  explicit LineReader(const fs::path& path) : fd_(io::open_regular(path, O_RDONLY, "--out")) {
    if (fd_ < 0) throw std::runtime_error("cannot open " + path.string() + ": " + std::strerror(errno));
  }
  ~LineReader() { ::close(fd_); }
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;
  bool next(std::string& line, std::uint64_t& offset) {
    offset = pos_;
    line.clear();
    for (;;) {
      if (at_ == end_ && !fill()) {  // end of file: what was read has no newline after it
        if (!line.empty()) torn_ = true;
        return false;
      }
      const char* nl = static_cast<const char*>(std::memchr(buf_ + at_, '\n', end_ - at_));
      const std::size_t take = nl ? static_cast<std::size_t>(nl - (buf_ + at_)) : end_ - at_;
      line.append(buf_ + at_, take);
      at_ += take;
      if (nl) {
        ++at_;
        pos_ += line.size() + 1;
        return true;
      }
    }
  }
  bool torn() const { return torn_; }
  std::uint64_t offset() const { return pos_; }  // bytes of the complete lines read

 private:
  bool fill() {
    for (;;) {
      const ssize_t n = ::read(fd_, buf_, sizeof buf_);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw std::runtime_error(std::string("cannot read a store file: ") + std::strerror(errno));
      at_ = 0, end_ = static_cast<std::size_t>(n);
      return n > 0;
    }
  }
  int fd_;
  char buf_[1 << 16];
  std::size_t at_ = 0, end_ = 0;
  std::uint64_t pos_ = 0;
  bool torn_ = false;
};

// Field `col` of a CSV row (RFC 4180 quoting, returned as written, quotes included), without
// splitting the whole row; false when the row has fewer fields.
bool csv_field_at(std::string_view row, std::size_t col, std::string_view& out) {
  std::size_t start = 0;
  for (std::size_t f = 0;; ++f) {
    std::size_t i = start;
    if (i < row.size() && row[i] == '"') {
      for (++i; i < row.size(); ++i)
        if (row[i] == '"') {
          if (i + 1 < row.size() && row[i + 1] == '"')
            ++i;
          else
            break;
        }
    }
    const std::size_t comma = row.find(',', i);
    const std::size_t end = comma == std::string_view::npos ? row.size() : comma;
    if (f == col) {
      out = row.substr(start, end - start);
      return true;
    }
    if (comma == std::string_view::npos) return false;
    start = comma + 1;
  }
}

// An upper bound on the number of rows of a store file: every line holds at least one byte per
// column (the commas and newline), 16 for the hash and, in the journal, 17 for the checksum.
std::size_t max_rows(const fs::path& file, const std::string& header, bool journal) {
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (ec) return 0;
  const std::size_t cols = static_cast<std::size_t>(std::count(header.begin(), header.end(), ',')) + 1;
  return static_cast<std::size_t>(size / (cols + 16 + (journal ? 17 : 0)));
}

}  // namespace

std::size_t Journal::status_column(const std::string& header) {
  const auto cols = io::csv_split(header);
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (cols[i] == "status") return i;
  throw std::runtime_error("store header has no status column");
}

void RowIndex::settle() {
  if (settled_ == v_.size()) return;
  // In place (no second copy): by index, then by offset, so the last row written of an index is
  // the last of its run; keep that one.
  std::sort(v_.begin(), v_.end(), [](const StoredRow& a, const StoredRow& b) {
    return a.index != b.index ? a.index < b.index : a.at < b.at;
  });
  std::size_t out = 0;
  for (std::size_t i = 0; i < v_.size(); ++i) {
    if (out > 0 && v_[out - 1].index == v_[i].index) --out;
    v_[out++] = v_[i];
  }
  v_.resize(out);
  settled_ = out;
}

const StoredRow* RowIndex::find(std::uint64_t index) const {
  const auto r = rows();
  const auto it =
      std::lower_bound(r.begin(), r.end(), index, [](const StoredRow& e, std::uint64_t i) { return e.index < i; });
  return it != r.end() && it->index == index ? &*it : nullptr;
}

void Journal::add_entry(std::string_view row, std::uint64_t offset) {
  const std::size_t comma = row.find(',');
  std::uint64_t index = 0;
  std::string_view status;
  if (comma == std::string_view::npos || !parse_u64(row.substr(0, comma), index) ||
      !csv_field_at(row, status_col_, status))
    throw std::runtime_error("malformed journal row (checksum good): " + std::string(row.substr(0, 60)));
  index_.add(index, offset, status == "ok");
}

// Indexes the rows of journal.csv, streamed; false when it holds lines to drop (a torn last line,
// bad checksums, no header), which are counted in dropped_.
bool Journal::scan(const fs::path& path) {
  index_.clear();
  LineReader in(path);
  std::string line;
  std::uint64_t offset = 0;
  if (!in.next(line, offset)) {
    dropped_ += in.torn() ? 1 : 0;
    return false;
  }
  const std::optional<io::JournalDigest> digest = io::journal_digest_of(line, header_);
  if (!digest)
    throw io::InputError(
        path.string(), 1, "header",
        "written for another campaign or version (its header differs); use another --out or remove the store");
  digest_ = *digest;
  bool clean = digest_ == io::JournalDigest::sha256;  // a legacy journal is rewritten with SHA-256
  while (in.next(line, offset)) {
    std::string_view row;
    if (io::checked_journal_row(line, row, digest_))
      add_entry(row, offset);
    else
      ++dropped_, clean = false;
  }
  if (in.torn()) ++dropped_, clean = false;
  size_ = in.offset();
  index_.settle();
  return clean;
}

Journal::Journal(const fs::path& dir, const std::string& header, JournalSync sync, std::uint64_t room)
    : header_(header), status_col_(status_column(header)), policy_(sync), last_sync_(std::chrono::steady_clock::now()) {
  if (policy_.every == 0) policy_.every = 1;
  const fs::path path = dir / "journal.csv";
  // Room for every row the file can hold and for the rows to append: virtual memory, touched as
  // rows are added, and the index never moves while this object appends at most `room` rows.
  const fs::path sized = fs::exists(path) || !fs::exists(dir / "points.csv") ? path : dir / "points.csv";
  index_.reserve(max_rows(sized, header_, sized == path) + static_cast<std::size_t>(room));
  const std::string head = io::journal_header(header_) + "\n";
  std::string line;
  std::uint64_t offset = 0;
  bool indexed = false;
  if (!fs::exists(path) && fs::exists(dir / "points.csv")) {
    // A store without its journal (e.g. a committed one: only points.csv is kept in git).
    // points.csv is only ever written atomically, so its rows seed the journal as they are.
    LineReader in(dir / "points.csv");
    if (!in.next(line, offset) || line != header_)
      throw std::runtime_error((dir / "points.csv").string() +
                               " was written for another campaign or version "
                               "(header differs); use another --out or remove the store");
    io::AtomicFileWriter out(path, io::Durability::synced);
    out.write(head);
    while (in.next(line, offset)) out.write(io::journal_line(line));
    out.commit();
  } else if (!fs::exists(path)) {
    io::write_file_durably(path, head);
  } else if (scan(path)) {
    indexed = true;  // intact: appended to as it is
  } else {
    // Recovered: rewritten atomically without the torn or corrupt lines (streamed), every line
    // with SHA-256 (a legacy journal's FNV-1a lines are checked as such, then re-digested).
    io::AtomicFileWriter out(path, io::Durability::synced);
    out.write(head);
    LineReader in(path);
    for (bool first = true; in.next(line, offset); first = false) {
      std::string_view row;
      if (!first && io::checked_journal_row(line, row, digest_)) out.write(io::journal_line(row));
    }
    out.commit();
    digest_ = io::JournalDigest::sha256;
  }
  file_ = std::make_unique<JournalFile>(path, true, "journal.csv");
  if (!indexed) {  // the offsets into the file as it is now
    const std::size_t dropped = dropped_;
    scan(path);
    dropped_ = dropped;
  }
}

Journal::~Journal() {
  if (file_ && unsynced_ > 0) file_->try_sync();  // no throwing here: a failure leaves rows to rerun
}

void Journal::append(const std::string& row) {
  const std::uint64_t at = size_;
  size_ += file_->append(row);
  add_entry(row, at);
  ++unsynced_;
  if (unsynced_ >= policy_.every ||
      (policy_.seconds > 0 &&
       std::chrono::duration<double>(std::chrono::steady_clock::now() - last_sync_).count() >= policy_.seconds))
    sync();
}

void Journal::sync() {
  if (unsynced_ == 0) return;
  if (before_sync_) before_sync_();
  file_->sync();
  unsynced_ = 0;
  ++syncs_;
  last_sync_ = std::chrono::steady_clock::now();
}

std::string Journal::row(const StoredRow& e) const {
  std::string line = file_->line_at(e.offset());
  line.resize(io::journal_row(line).size());  // without ",digest"
  return line;
}

std::string Journal::write_points(const fs::path& dir, const std::function<bool(std::uint64_t)>& keep) {
  settle();
  io::AtomicFileWriter out(dir / "points.csv", io::Durability::synced);
  io::Sha256 digest;
  const auto put = [&](const std::string& text) {
    out.write(text);
    digest.update(text);
  };
  put(header_ + "\n");
  for (const StoredRow& e : entries())
    if (keep(e.index)) put(row(e) + "\n");
  out.commit();
  return digest.hex();
}

StoreReader::StoreReader(const fs::path& dir) {
  file_ = dir / "journal.csv";
  const bool journal = fs::exists(file_);
  if (!journal) {  // a store without its journal (e.g. committed): its points.csv
    file_ = dir / "points.csv";
    if (!fs::exists(file_))
      throw io::InputError(dir.string(), 0, "", "not a sweep store (no journal.csv or points.csv)");
  }
  LineReader in(file_);
  std::string line;
  std::uint64_t offset = 0;
  if (!in.next(line, offset)) throw io::InputError(file_.string(), 0, "", "empty file, not a sweep store");
  header_ = line;
  io::JournalDigest digest = io::JournalDigest::sha256;
  if (journal) {
    header_.resize(io::journal_row(line).size());
    const std::optional<io::JournalDigest> d = io::journal_digest_of(line, header_);
    if (!d) throw io::InputError(file_.string(), 1, "", "malformed journal header");
    digest = *d;
  }
  journal_ = journal;
  rows_.reserve(max_rows(file_, header_, journal));
  while (in.next(line, offset)) {
    std::string_view row = line;
    if (journal && !io::checked_journal_row(line, row, digest)) continue;
    const std::size_t comma = row.find(',');
    std::uint64_t index = 0;
    if (comma != std::string_view::npos && parse_u64(row.substr(0, comma), index)) rows_.add(index, offset, false);
  }
  rows_.settle();
  fd_ = io::open_regular(file_, O_RDONLY, "--out");
  if (fd_ < 0) sys_fail("cannot open", file_);
}

StoreReader::~StoreReader() {
  if (fd_ >= 0) ::close(fd_);
}

StoreReader::StoreReader(StoreReader&& o) noexcept
    : file_(std::move(o.file_)),
      header_(std::move(o.header_)),
      rows_(std::move(o.rows_)),
      journal_(o.journal_),
      fd_(o.fd_) {
  o.fd_ = -1;
}

std::string StoreReader::row(const StoredRow& r) const {
  std::string line = read_line_at(fd_, r.offset(), file_.string());
  if (journal_) line.resize(io::journal_row(line).size());  // without ",digest"
  return line;
}

namespace {

std::string series_header(const std::vector<std::string>& columns) {
  std::string h = "index";
  for (const std::string& c : columns) h += "," + c;
  return h;
}

// "#end,INDEX,HASH,ROWS,CHECKSUM" → its fields; false when malformed.
bool parse_trailer(std::string_view line, std::uint64_t& index, std::uint64_t& hash, std::uint64_t& rows,
                   std::uint64_t& sum) {
  if (line.rfind("#end,", 0) != 0) return false;
  std::string_view f[4];
  std::size_t at = 5;
  for (int k = 0; k < 4; ++k) {
    const std::size_t comma = k < 3 ? line.find(',', at) : line.size();
    if (comma == std::string_view::npos) return false;
    f[k] = line.substr(at, comma - at);
    at = comma + 1;
  }
  return parse_u64(f[0], index) && parse_u64(f[1], hash, 16) && parse_u64(f[2], rows) && parse_u64(f[3], sum, 16);
}

}  // namespace

std::string series_block(std::uint64_t index, std::uint64_t hash, const std::string& rows) {
  std::uint64_t n = 0;
  for (const char c : rows) n += c == '\n' ? 1 : 0;
  return rows + "#end," + std::to_string(index) + "," + io::hex16(hash) + "," + std::to_string(n) + "," +
         io::hex16(io::fnv1a64(rows)) + "\n";
}

SeriesFile::SeriesFile(const fs::path& dir, bool append, const std::vector<std::string>& columns)
    : path_(dir / "series.csv") {
  if (append && !fs::exists(path_)) io::write_file_durably(path_, series_header(columns) + "\n");
  // Index the whole blocks; the good prefix ends after the last one that is whole (a block is
  // whole when its trailer names its index and its row count and the checksum of its rows
  // matches; anything after the first bad one is a torn or corrupt tail).
  LineReader in(path_);
  std::string line;
  std::uint64_t offset = 0;
  if (!in.next(line, offset) || line.rfind("index", 0) != 0)
    throw std::runtime_error(path_.string() + ": not a store's series file (no header)");
  header_ = line;
  const auto names = io::csv_split(line);
  columns_.assign(names.begin() + 1, names.end());
  if (!columns.empty() && line != series_header(columns))
    throw std::runtime_error(path_.string() + " holds series columns " + line + ", the campaign asks for " +
                             series_header(columns) + "; use another --out or remove the store");
  std::uint64_t good_end = in.offset(), block_start = good_end, rows = 0, sum = io::fnv1a64(std::string_view());
  std::uint64_t first_index = 0;
  bool bad = false;
  std::vector<SeriesBlock> all;
  while (!bad && in.next(line, offset)) {
    if (line.rfind("#end,", 0) == 0) {
      std::uint64_t index = 0, hash = 0, n = 0, want = 0;
      if (!parse_trailer(line, index, hash, n, want) || n != rows || want != sum ||
          (rows > 0 && index != first_index)) {
        bad = true;
        break;
      }
      all.push_back({index, hash, block_start, offset});
      good_end = in.offset(), block_start = good_end, rows = 0, sum = io::fnv1a64(std::string_view());
      continue;
    }
    std::uint64_t index = 0;
    const std::size_t comma = line.find(',');
    if (!parse_u64(std::string_view(line).substr(0, comma), index) || (rows > 0 && index != first_index)) {
      bad = true;
      break;
    }
    first_index = index;
    ++rows;
    sum = io::fnv1a64_extend(io::fnv1a64_extend(sum, line), "\n");
  }
  const std::uint64_t file_size = fs::file_size(path_);
  dropped_ = static_cast<std::size_t>(file_size - good_end);
  // Last block of each index, sorted (stable: file order within an index).
  std::stable_sort(all.begin(), all.end(),
                   [](const SeriesBlock& a, const SeriesBlock& b) { return a.index < b.index; });
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (!blocks_.empty() && blocks_.back().index == all[i].index) {
      blocks_.back() = all[i];
      superseded_ = true;
    } else {
      blocks_.push_back(all[i]);
    }
  }
  fd_ = io::open_regular(path_, append ? O_RDWR | O_APPEND : O_RDONLY, "--out");
  if (fd_ < 0) sys_fail("cannot open", path_);
  if (append && dropped_ > 0) {  // cut off the torn tail, durably, before appending after it
    if (::ftruncate(fd_, static_cast<off_t>(good_end)) != 0 || ::fdatasync(fd_) != 0)
      sys_fail("cannot truncate", path_);
  }
  size_ = good_end;
}

SeriesFile::~SeriesFile() {
  if (fd_ < 0) return;
  if (unsynced_) ::fdatasync(fd_);
  ::close(fd_);
}

const SeriesBlock* SeriesFile::find(std::uint64_t index) const {
  const auto it = std::lower_bound(blocks_.begin(), blocks_.end(), index,
                                   [](const SeriesBlock& b, std::uint64_t i) { return b.index < i; });
  return it != blocks_.end() && it->index == index ? &*it : nullptr;
}

std::string SeriesFile::rows(const SeriesBlock& b) const {
  std::string s(b.end - b.offset, '\0');
  std::size_t got = 0;
  while (got < s.size()) {
    const ssize_t r = ::pread(fd_, s.data() + got, s.size() - got, static_cast<off_t>(b.offset + got));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) throw std::runtime_error("cannot read " + path_.string());
    got += static_cast<std::size_t>(r);
  }
  return s;
}

void SeriesFile::append(std::uint64_t index, std::uint64_t hash, const std::string& rows) {
  const std::string block = series_block(index, hash, rows);
  if (!io::write_fully(fd_, block)) sys_fail("cannot write", path_);
  size_ += block.size();
  unsynced_ = true;
  if (find(index)) superseded_ = true;
  appended_.push_back(index);
}

void SeriesFile::sync() {
  if (!unsynced_) return;
  if (::fdatasync(fd_) != 0) sys_fail("cannot sync", path_);
  unsynced_ = false;
}

void SeriesFile::compact(const std::function<bool(std::uint64_t, std::uint64_t)>& keep) {
  sync();
  // Re-index the file as it is now (appended blocks included): a reader of the current bytes.
  const SeriesFile now(path_.parent_path(), false);
  io::AtomicFileWriter out(path_, io::Durability::synced);
  out.write(header_ + "\n");
  for (const SeriesBlock& b : now.blocks_)
    if (keep(b.index, b.hash)) {
      out.write(series_block(b.index, b.hash, now.rows(b)));
    }
  out.commit();
  // This object's descriptor still names the old file: reopen for appending.
  ::close(fd_);
  fd_ = io::open_regular(path_, O_RDWR | O_APPEND, "--out");
  if (fd_ < 0) sys_fail("cannot open", path_);
  size_ = fs::file_size(path_);
  superseded_ = false;
}

std::map<std::uint64_t, std::string> read_point_series(const fs::path& dir, const std::vector<std::uint64_t>& indices) {
  const StoreReader store(dir);
  std::unique_ptr<SeriesFile> series;
  if (fs::exists(dir / "series.csv")) series = std::make_unique<SeriesFile>(dir, false);
  std::map<std::uint64_t, std::string> out;
  const auto rows = store.rows();
  for (const std::uint64_t index : indices) {
    const auto it = std::lower_bound(rows.begin(), rows.end(), index,
                                     [](const StoredRow& e, std::uint64_t i) { return e.index < i; });
    if (it == rows.end() || it->index != index) continue;
    const std::string row = store.row(*it);
    const std::size_t a = row.find(',') + 1, b = row.find(',', a);
    const std::string hash = row.substr(a, b - a);
    if (series) {
      const SeriesBlock* blk = series->find(index);
      if (!blk || io::hex16(blk->hash) != hash) continue;
      std::string text;
      for (std::size_t j = 0; j < series->columns().size(); ++j) text += (j ? "," : "") + series->columns()[j];
      text += '\n';
      const std::string block = series->rows(*blk);
      for (std::size_t at = 0; at < block.size();) {  // each row without its leading "index,"
        const std::size_t comma = block.find(',', at), nl = block.find('\n', at);
        text.append(block, comma + 1, nl + 1 - (comma + 1));
        at = nl + 1;
      }
      out[index] = std::move(text);
    } else if (const fs::path f = dir / "series" / (hash + ".csv"); fs::exists(f)) {
      out[index] = io::read_file_text(f);
    }
  }
  return out;
}

}  // namespace asperity
