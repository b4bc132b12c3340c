#include "campaign/store.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace asperity {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void sys_fail(const std::string& what, const fs::path& p) {
  throw std::runtime_error(what + " " + p.string() + ": " + std::strerror(errno));
}

void write_all(int fd, const char* data, std::size_t n, const fs::path& p) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      sys_fail("cannot write", p);
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
}

void fsync_dir(const fs::path& dir) {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
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

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

std::string hex16(std::uint64_t h) {
  static const char* digits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) s[static_cast<std::size_t>(i)] = digits[h & 0xf];
  return s;
}

std::string csv_field(std::string_view in) {
  std::string s(in);
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  const bool quote = s.find_first_of(",\"") != std::string::npos ||
                     (!s.empty() && (s.front() == ' ' || s.back() == ' ' || s.front() == '\t'));
  if (!quote) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::vector<std::string> csv_split(std::string_view line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false, in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
        else in_quotes = false;
      } else {
        cur += c;
      }
    } else if (c == '"' && cur.empty() && !quoted) {
      in_quotes = quoted = true;
    } else if (c == ',') {
      out.push_back(std::move(cur));
      cur.clear();
      quoted = false;
    } else {
      cur += c;
    }
  }
  if (in_quotes) throw std::runtime_error("unterminated quote in CSV line");
  out.push_back(std::move(cur));
  return out;
}

std::string read_file_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_file_durably(const fs::path& path, const std::string& text) {
  static std::atomic<unsigned> counter{0};  // several threads may write files of one folder
  std::string name = ".";  // (built by append: GCC 12 warns falsely on "." + std::string)
  name.append(path.filename().string()).append(".tmp-").append(std::to_string(::getpid()));
  name.append("-").append(std::to_string(counter++));
  const fs::path tmp = path.parent_path() / name;
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) sys_fail("cannot create", tmp);
  write_all(fd, text.data(), text.size(), tmp);
  if (::fsync(fd) != 0 || ::close(fd) != 0) sys_fail("cannot write", tmp);
  if (::rename(tmp.c_str(), path.c_str()) != 0) sys_fail("cannot rename into", path);
  fsync_dir(path.parent_path().empty() ? fs::path(".") : path.parent_path());
}

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

Journal::Journal(const fs::path& dir, const std::string& header)
    : header_(header), status_col_(status_column(header)) {
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
  if (fd_ >= 0) ::close(fd_);
}

void Journal::append(const std::string& row) {
  const std::string line = row + "," + hex16(fnv1a64(row)) + "\n";
  write_all(fd_, line.data(), line.size(), "journal.csv");
  if (::fdatasync(fd_) != 0) sys_fail("cannot sync", "journal.csv");
  add_entry(row, size_);
  size_ += line.size();
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
