#include "fit/fit_journal.hpp"

#include <charconv>
#include <fstream>
#include <stdexcept>

#include "batch/inputs_fingerprint.hpp"
#include "fit/fit_inputs.hpp"
#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/journal_line.hpp"
#include "io/numbers.hpp"
#include "io/safe_open.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

const char* const kColumnsLine = "part,optimization,evaluation,x,objective,terms,status,wall_s";
const char* const kColumns[] = {"part", "optimization", "evaluation", "x", "objective", "terms", "status", "wall_s"};

std::string key_of(const std::string& part, const std::string& optimization, const std::string& x) {
  return part + '\n' + optimization + '\n' + x;
}

// A number as the journal writes it (csv_number; "nan" for a failed evaluation's objective).
bool parse_number(std::string_view s, double& out) {
  const auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
}

bool parse_list(std::string_view s, std::vector<double>& out) {
  out.clear();
  if (s.empty()) return true;
  for (std::size_t start = 0;;) {
    const std::size_t semi = s.find(';', start);
    double v = 0;
    if (!parse_number(s.substr(start, semi == std::string_view::npos ? std::string_view::npos : semi - start), v))
      return false;
    out.push_back(v);
    if (semi == std::string_view::npos) return true;
    start = semi + 1;
  }
}

}  // namespace

std::string journal_values(const std::vector<double>& x) {
  std::string s;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (i) s += ';';
    s += io::csv_number(x[i]);
  }
  return s;
}

FitJournal::~FitJournal() = default;

void FitJournal::open(const fs::path& file, bool append) { read(file, append && !file_); }

namespace {

// One evaluation from the fields of a good line (InputError "FILE:LINE: KEY: ..." when malformed).
Evaluation parse_evaluation(const std::vector<std::string>& f, const std::string& name, int lineno) {
  if (f.size() != 8)
    throw io::InputError(name, lineno, f.size() < 8 ? kColumns[f.size()] : "check",
                         "expected 8 fields and a checksum, got " + std::to_string(f.size()) + " fields");
  Evaluation ev;
  if (!io::parse_int(f[2], ev.index) || ev.index < 1)
    throw io::InputError(name, lineno, "evaluation", "not a positive whole number: " + io::quote(f[2]));
  if (!parse_list(f[3], ev.values) || ev.values.empty())
    throw io::InputError(name, lineno, "x", "not a ';'-separated list of numbers: " + io::quote(f[3]));
  if (!parse_number(f[4], ev.objective))
    throw io::InputError(name, lineno, "objective", "not a number: " + io::quote(f[4]));
  if (!parse_list(f[5], ev.residuals))
    throw io::InputError(name, lineno, "terms", "not a ';'-separated list of numbers: " + io::quote(f[5]));
  if (f[6].empty()) throw io::InputError(name, lineno, "status", "empty");
  ev.status = f[6];
  if (!parse_number(f[7], ev.wall_s)) throw io::InputError(name, lineno, "wall_s", "not a number: " + io::quote(f[7]));
  return ev;
}

// What a strict read of a journal's text found.
struct JournalScan {
  std::uint64_t good_end = 0;  // bytes up to the end of the last good line
  io::JournalDigest digest = io::JournalDigest::sha256;
  std::size_t dropped = 0;                                  // torn or damaged tail lines
  std::map<std::string, std::pair<Evaluation, int>> found;  // key → evaluation, line
};

// Reads a journal strictly: a torn last line, or a tail of damaged lines after the last good one
// (a kill, a power cut before the flush), is dropped; a damaged line followed by good ones, a
// wrong header or a malformed field is InputError.
JournalScan scan_journal(const std::string& text, const std::string& name) {
  JournalScan scan;
  std::string line;
  std::uint64_t offset = 0;
  int lineno = 0;
  int first_bad = 0;  // a damaged line: fatal if a good one follows, a dropped tail otherwise
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t nl = text.find('\n', at);
    line.assign(text, at, nl == std::string::npos ? std::string::npos : nl - at);
    at = nl == std::string::npos ? text.size() : nl + 1;
    ++lineno;
    const bool whole = nl != std::string::npos;  // a last line without its newline is torn
    const std::uint64_t end = offset + line.size() + (whole ? 1 : 0);
    offset = end;
    if (lineno == 1) {
      if (!whole) break;  // torn header: as good as an empty journal
      const std::optional<io::JournalDigest> d = io::journal_digest_of(line, kColumnsLine);
      if (!d)
        throw io::InputError(name, 1, "header",
                             "not an asperity fit journal (expected '" + io::journal_header(kColumnsLine) + "')");
      scan.digest = *d;
      scan.good_end = end;
      continue;
    }
    std::string_view row;
    if (!whole || !io::checked_journal_row(line, row, scan.digest)) {
      if (first_bad == 0) first_bad = lineno;
      continue;
    }
    if (first_bad != 0)
      throw io::InputError(
          name, first_bad, "check",
          "damaged line (its checksum does not match) followed by good ones: the journal was edited or "
          "corrupted; remove that line or the folder");
    std::vector<std::string> f;
    try {
      f = io::csv_split(row);
    } catch (const std::exception& e) {
      throw io::InputError(name, lineno, "part", e.what());
    }
    Evaluation ev = parse_evaluation(f, name, lineno);
    scan.good_end = end;
    scan.found[key_of(f[0], f[1], f[3])] = {std::move(ev), lineno};
  }
  if (first_bad != 0) scan.dropped = static_cast<std::size_t>(lineno - first_bad + 1);
  return scan;
}

// A journal from before SHA-256: its good lines (checked with FNV-1a) re-digested, under a new header.
std::string redigested(std::string_view text, io::JournalDigest digest) {
  std::string out = io::journal_header(kColumnsLine) + "\n";
  std::size_t at = text.find('\n') + 1;
  for (std::size_t nl; at < text.size() && (nl = text.find('\n', at)) != std::string::npos; at = nl + 1) {
    std::string_view row;
    if (io::checked_journal_row(text.substr(at, nl - at), row, digest)) out += io::journal_line(row);
  }
  return out;
}

}  // namespace

void FitJournal::read(const fs::path& file, bool append) {
  const std::string name = file.string();
  JournalScan scan;
  // Read without following a link, a regular file only (a FIFO would block): io/safe_open.hpp.
  std::string text;
  if (io::read_regular(file, text, "--out")) {
    scan = scan_journal(text, name);
    dropped_ += scan.dropped;
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [k, ev] : scan.found)  // the first file read wins
      if (index_.emplace(k, std::move(ev.first)).second) where_.emplace(k, std::make_pair(name, ev.second));
  }
  files_.push_back(file);
  if (!append) return;
  // A file written afresh here (no header yet, or a torn one; a legacy journal re-digested) is
  // exactly what was written: it has no tail to cut (cutting at the old text's good end would cut
  // the fresh header away).
  bool rewritten = true;
  if (scan.good_end == 0) {
    io::write_file_durably(file, io::journal_header(kColumnsLine) + "\n");
  } else if (scan.digest == io::JournalDigest::fnv1a64_legacy) {
    // Written atomically in its place; a torn or damaged tail goes with it.
    text.resize(scan.good_end);
    io::write_file_durably(file, redigested(text, scan.digest));
  } else {
    rewritten = false;
  }
  file_ = std::make_unique<JournalFile>(file, false, name);
  if (!rewritten && scan.good_end < text.size())
    file_->cut(scan.good_end);  // only a torn or damaged tail: nothing computed is lost
  else
    file_->sync();
}

std::optional<Evaluation> FitJournal::find(const std::string& part, const std::string& optimization,
                                           const std::vector<double>& x) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = index_.find(key_of(part, optimization, journal_values(x)));
  if (it == index_.end()) return std::nullopt;
  return it->second;
}

void FitJournal::append(const std::string& part, const std::string& optimization, const Evaluation& ev) {
  const std::string x = journal_values(ev.values);
  const std::string row = io::csv_field(part) + "," + io::csv_field(optimization) + "," + std::to_string(ev.index) +
                          "," + x + "," + io::csv_number(ev.objective) + "," + journal_values(ev.residuals) + "," +
                          io::csv_field(ev.status) + "," + io::csv_number(ev.wall_s);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!file_) throw std::logic_error("FitJournal::append: no journal opened for appending");
  file_->append_durably(row);
  index_.emplace(key_of(part, optimization, x), ev);
}

std::optional<std::pair<std::string, int>> FitJournal::where(const std::string& part, const std::string& optimization,
                                                             const std::vector<double>& x) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = where_.find(key_of(part, optimization, journal_values(x)));
  if (it == where_.end()) return std::nullopt;
  return it->second;
}

std::size_t FitJournal::size() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return index_.size();
}

std::unique_ptr<io::DirLock> lock_fit_journal_dir(const fs::path& dir, const std::string& option) {
  try {
    return std::make_unique<io::DirLock>(dir, "asperity fit");
  } catch (const std::runtime_error& e) {
    throw io::InputError(dir.string(), 0, option, e.what());
  }
}

void open_fit_journal(FitJournal& journal, const fs::path& dir, const std::string& inputs) {
  const fs::path file = dir / "journal.csv", in = dir / kInputsFileName;
  if (fs::exists(file)) {
    if (!fs::exists(in))
      throw io::InputError(file.string(), 0, "",
                           "no inputs.txt beside it, so what its evaluations were computed from is "
                           "unknown; use another --out or remove the folder");
    check_fit_inputs(in, inputs);
  } else {
    write_inputs(dir, inputs);
  }
  journal.open(file, true);
}

}  // namespace asperity
