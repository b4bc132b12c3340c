#include "io/yaml_util.hpp"

#include <yaml-cpp/anchor.h>
#include <yaml-cpp/eventhandler.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>
#include <vector>

#include "io/numbers.hpp"
#include "io/warnings.hpp"

namespace asperity::io {

namespace {

int mark_line(const YAML::Node& n) {
  if (!n.IsDefined()) return 0;
  const YAML::Mark m = n.Mark();
  return m.is_null() ? 0 : m.line + 1;
}

bool under(const std::string& key, const std::string& prefix) {
  return key.size() > prefix.size() && key.compare(0, prefix.size(), prefix) == 0 && key[prefix.size()] == '.';
}

}  // namespace

std::pair<std::string, int> value_origin(const Source& src, const YAML::Node& at, const std::string& key,
                                         int fallback_line) {
  if (const int line = mark_line(at); line > 0) return {src.file, line};
  if (src.sets) {
    for (auto it = src.sets->rbegin(); it != src.sets->rend(); ++it)
      if (key == it->key || under(key, it->key) || under(it->key, key)) return {it->text, 0};
  }
  return {src.file, fallback_line};
}

void fail(const Source& src, const YAML::Node& at, const std::string& key, const std::string& message,
          int fallback_line) {
  const auto [file, line] = value_origin(src, at, key, fallback_line);
  throw InputError(file, line, key, message);
}

std::string join_key(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

std::string node_kind(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  if (n.IsMap()) return "a map";
  if (n.IsSequence()) return "a list";
  return "the value " + quote(n.Scalar());
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  auto lc = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (lc(a[i - 1]) == lc(b[j - 1]) ? 0 : 1)});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string did_you_mean(const std::string& word, const std::vector<std::string>& candidates) {
  std::size_t best = 3;
  const std::string* pick = nullptr;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best && d < std::min(word.size(), c.size())) best = d, pick = &c;
  }
  return pick ? " (did you mean '" + *pick + "'?)" : "";
}

std::string misplaced_key_hint(const std::string& path, const std::string& key,
                               const std::vector<std::string>& layout) {
  const std::string here = join_key(path, key);
  std::vector<std::string> homes;
  for (const std::string& d : layout) {
    if (d == here) return "";
    const std::size_t dot = d.rfind('.');
    const std::string leaf = dot == std::string::npos ? d : d.substr(dot + 1);
    const std::string section = d.substr(0, d.find('.'));
    if (leaf == key && std::find(homes.begin(), homes.end(), d) == homes.end()) homes.push_back(d);
    if (section == key && !path.empty() && std::find(homes.begin(), homes.end(), section) == homes.end())
      homes.push_back(section);
  }
  if (homes.empty()) return "";
  return " (" + quote(key) + " is " + join(homes, " or ") + ": check its indentation)";
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

namespace {

std::string size_text(std::uintmax_t bytes) {
  char buf[32];
  if (bytes >= (std::uintmax_t{1} << 20) && bytes % (std::uintmax_t{1} << 20) == 0)
    std::snprintf(buf, sizeof buf, "%ju MiB", bytes >> 20);
  else if (bytes >= 1000000)
    std::snprintf(buf, sizeof buf, "%.3g MB", static_cast<double>(bytes) * 1e-6);
  else
    std::snprintf(buf, sizeof buf, "%ju bytes", bytes);
  return buf;
}

// "" when `st` describes a regular file of at most max_bytes.
std::string stat_problem(const struct stat& st, std::uintmax_t max_bytes) {
  if (S_ISDIR(st.st_mode)) return "is a directory, not a file";
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISCHR(st.st_mode)    ? "a character device"
                       : S_ISBLK(st.st_mode)  ? "a block device"
                       : S_ISFIFO(st.st_mode) ? "a FIFO (named pipe)"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                                              : "not a file";
    return std::string("is ") + kind + ", not a regular file";
  }
  const auto size = static_cast<std::uintmax_t>(st.st_size);
  if (size > max_bytes)
    return "is " + size_text(size) + ", more than the " + size_text(max_bytes) + " an input file of this kind may have";
  return "";
}

// Closes a file descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string input_file_problem(const std::filesystem::path& path, std::uintmax_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    return errno == ENOENT || errno == ENOTDIR ? "file not found" : std::strerror(errno);
  return stat_problem(st, max_bytes);
}

std::string read_input_file(const std::filesystem::path& path, const std::string& display, std::uintmax_t max_bytes) {
  // Checked by path first, so that a FIFO or device is never opened at all; then on the open
  // file (O_NONBLOCK: opening a FIFO swapped in meanwhile does not wait for a writer).
  if (std::string why = input_file_problem(path, max_bytes); !why.empty()) throw InputError(display, 0, "", why);
  const Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (f.fd < 0) throw InputError(display, 0, "", std::string("cannot open file: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0)
    throw InputError(display, 0, "", std::string("cannot read file: ") + std::strerror(errno));
  if (std::string why = stat_problem(st, max_bytes); !why.empty()) throw InputError(display, 0, "", why);
  std::string text;
  text.reserve(static_cast<std::size_t>(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(f.fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(display, 0, "", std::string("cannot read file: ") + std::strerror(errno));
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > max_bytes)  // grew while being read
      throw InputError(display, 0, "",
                       "is more than the " + size_text(max_bytes) + " an input file of this kind may have");
  }
  return text;
}

// YAML forbids C0 control characters other than tab, LF and CR (and DEL); yaml-cpp 0.7 can loop
// forever on some of them (found by tests/fuzz/fuzz_scene.cpp), so they are refused before parsing.
static void check_yaml_text(const std::string& text, const std::string& display, const std::string& key) {
  int line = 1, col = 0;
  for (unsigned char c : text) {
    ++col;
    if (c == '\n') {
      ++line;
      col = 0;
      continue;
    }
    if ((c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", c);
      throw InputError(display, key.empty() ? line : 0, key,
                       std::string("control character ") + hex + " is not allowed in YAML (binary file?)",
                       key.empty() ? col : 0);
    }
  }
}

// YAML text is Unicode (YAML 1.2 §5.2); bytes that are not UTF-8 would be carried into names and
// written back into outputs that other YAML readers (PyYAML) then refuse, so they are refused here.
static void check_utf8(const std::string& text, const std::string& display, const std::string& key) {
  int line = 1, col = 0;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    ++col;
    if (c == '\n') {
      ++line;
      col = 0;
      ++i;
      continue;
    }
    if (c < 0x80) {
      ++i;
      continue;
    }
    // Lead byte → sequence length and the smallest code point it may encode (no overlongs).
    const std::size_t len = c >= 0xC2 && c <= 0xDF ? 2 : c >= 0xE0 && c <= 0xEF ? 3 : c >= 0xF0 && c <= 0xF4 ? 4 : 0;
    bool ok = len != 0 && i + len <= text.size();
    std::uint32_t cp = ok ? c & (0x7F >> len) : 0;
    for (std::size_t k = 1; ok && k < len; ++k) {
      const auto b = static_cast<unsigned char>(text[i + k]);
      ok = (b & 0xC0) == 0x80;
      cp = (cp << 6) | (b & 0x3F);
    }
    ok = ok && !(len == 3 && cp < 0x800) && !(len == 4 && (cp < 0x10000 || cp > 0x10FFFF)) &&
         !(cp >= 0xD800 && cp <= 0xDFFF);
    if (!ok)
      throw InputError(display, key.empty() ? line : 0, key, "bytes that are not UTF-8 (YAML text must be UTF-8)",
                       key.empty() ? col : 0);
    i += len;
  }
}

namespace {
// Counts documents without building them. YAML::LoadAll loops forever on some malformed input
// (e.g. a lone ',': every call "finds" another empty document; found by tests/fuzz/fuzz_scene.cpp),
// so documents are counted with a cap instead.
//
// It also measures the document as it would be with every alias expanded (nodes plus scalar
// bytes): yaml-cpp shares an aliased node, but writing a scene or a campaign point back out
// expands it, and nested aliases grow geometrically (a "billion laughs" of 600 bytes re-emits as
// gigabytes). An anchor's size is known when it closes, so the sum is exact and costs O(events).
struct DocumentCounter : YAML::EventHandler {
  struct TooLarge {
    int line;
  };  // thrown out of the parser at the first alias over the limit
  int documents = 0;
  int second_line = 0;      // 1-based line where a second document starts
  std::uint64_t limit = 0;  // largest expanded size accepted
  std::uint64_t total = 0;  // expanded size of everything read so far
  std::map<YAML::anchor_t, std::uint64_t> anchor_size;
  struct Open {
    YAML::anchor_t anchor;
    std::uint64_t size;
  };
  std::vector<Open> open;  // collections being read, innermost last

  // A node of expanded size n (≤ limit, so no sum here can overflow) read at mark m.
  void count(std::uint64_t n, const YAML::Mark& m) {
    total += n;
    if (total > limit) throw TooLarge{m.line + 1};
  }
  void leaf(std::uint64_t n, YAML::anchor_t anchor, const YAML::Mark& m) {
    count(n, m);
    if (anchor != YAML::NullAnchor) anchor_size[anchor] = n;
    if (!open.empty()) open.back().size += n;
  }
  void OnDocumentStart(const YAML::Mark& m) override {
    if (++documents == 2) second_line = m.line + 1;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& m, YAML::anchor_t a) override { leaf(1, a, m); }
  void OnAlias(const YAML::Mark& m, YAML::anchor_t a) override {
    const auto it = anchor_size.find(a);
    leaf(it == anchor_size.end() ? 1 : it->second, YAML::NullAnchor, m);
  }
  void OnScalar(const YAML::Mark& m, const std::string&, YAML::anchor_t a, const std::string& v) override {
    leaf(1 + v.size(), a, m);
  }
  void OnSequenceStart(const YAML::Mark& m, const std::string&, YAML::anchor_t a, YAML::EmitterStyle::value) override {
    count(1, m);
    open.push_back({a, 1});
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& m, const std::string&, YAML::anchor_t a, YAML::EmitterStyle::value) override {
    count(1, m);
    open.push_back({a, 1});
  }
  void OnMapEnd() override { close(); }
  // A closed collection's size is already in `total` (its own node and its items); it only
  // moves into its parent's size and, when anchored, becomes what an alias to it costs.
  void close() {
    const Open o = open.back();
    open.pop_back();
    if (o.anchor != YAML::NullAnchor) anchor_size[o.anchor] = o.size;
    if (!open.empty()) open.back().size += o.size;
  }
};

// The 1-based line of the first line whose indentation holds a tab (0: none).
int first_tab_indented_line(const std::string& text) {
  int line = 1;
  bool indent = true;
  for (const char c : text) {
    if (c == '\n') {
      ++line;
      indent = true;
    } else if (indent && c == '\t') {
      return line;
    } else if (c != ' ') {
      indent = false;
    }
  }
  return 0;
}

// The one document of `text` (Null when empty); parse errors and extra documents → InputError.
YAML::Node load_one_document(const std::string& text, const std::string& display, const std::string& key) {
  const int line_of = key.empty() ? 1 : 0;  // a --set value has no file line
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentCounter counter;
    counter.limit = std::max<std::uint64_t>(kMaxYamlExpansion, 4 * text.size());
    try {
      while (counter.documents < 2 && parser.HandleNextDocument(counter)) {
      }
    } catch (const DocumentCounter::TooLarge& big) {
      throw InputError(display, line_of * big.line, key,
                       "aliases (*name) expand this YAML to more than " + std::to_string(counter.limit) +
                           " nodes and characters; write the values out instead of nesting aliases");
    }
    if (counter.documents > 1) {
      const bool marker = text.find("---") != std::string::npos || text.find("...") != std::string::npos;
      throw InputError(display, line_of * counter.second_line, key,
                       marker ? "more than one YAML document ('---'); the file must hold exactly one"
                              : "malformed YAML: content outside any map or list (a stray ',' or ']'?)");
    }
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    // YAML indents with spaces only; a tab there is the usual cause, and yaml-cpp names it
    // only as the map or value it then cannot read.
    if (const int tab = first_tab_indented_line(text); tab > 0 && (e.mark.is_null() || tab <= e.mark.line + 1))
      throw InputError(display, line_of * tab, key,
                       "malformed YAML: this line is indented with a tab; YAML indents with spaces only");
    throw InputError(display, line_of * (e.mark.is_null() ? 0 : e.mark.line + 1), key,
                     (key.empty() ? "malformed YAML: " : "malformed YAML value: ") + e.msg);
  }
}
}  // namespace

YAML::Node load_yaml_file(const std::filesystem::path& path, const std::string& display) {
  return load_yaml_document(read_input_file(path, display, kMaxYamlBytes), display);
}

YAML::Node load_yaml_document(const std::string& text, const std::string& display) {
  check_yaml_text(text, display, "");
  YAML::Node doc = load_one_document(text, display, "");  // malformed YAML is named first
  check_utf8(text, display, "");
  return doc;
}

YAML::Node load_yaml_text(const std::string& text, const std::string& where, const std::string& key) {
  check_yaml_text(text, where, key);
  YAML::Node doc = load_one_document(text, where, key);
  check_utf8(text, where, key);
  return strip_marks(doc);
}

YAML::Node strip_marks(const YAML::Node& n) {
  if (!n.IsDefined()) return YAML::Node(YAML::NodeType::Null);
  switch (n.Type()) {
    case YAML::NodeType::Scalar:
      return YAML::Node(n.Scalar());
    case YAML::NodeType::Sequence: {
      YAML::Node out(YAML::NodeType::Sequence);
      for (const auto& c : n) out.push_back(strip_marks(c));
      return out;
    }
    case YAML::NodeType::Map: {
      YAML::Node out(YAML::NodeType::Map);
      for (auto it = n.begin(); it != n.end(); ++it) out[strip_marks(it->first)] = strip_marks(it->second);
      return out;
    }
    default:
      return YAML::Node(YAML::NodeType::Null);
  }
}

MapView::MapView(Source src, const YAML::Node& node, std::string path, std::vector<std::string> allowed,
                 int fallback_line)
    : src_(std::move(src)), node_(node), path_(std::move(path)), fallback_line_(fallback_line) {
  if (!node_.IsDefined() || node_.IsNull()) return;
  if (!node_.IsMap())
    fail(src_, node_, path_, "expected a map of 'key: value' entries, got " + node_kind(node_), fallback_line_);
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const YAML::Node kn = it->first;
    if (!kn.IsScalar()) fail(src_, kn, path_, "keys must be plain names, got " + node_kind(kn), fallback_line_);
    const std::string k = kn.Scalar();
    for (const auto& e : entries_)
      if (e.first == k)
        fail(src_, kn, key(k), "duplicate key (first given at line " + std::to_string(mark_line(e.second.first)) + ")",
             fallback_line_);
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      fail(src_, kn, key(k),
           "unknown key " + quote(k) + did_you_mean(k, allowed) +
               (src_.layout ? misplaced_key_hint(path_, k, *src_.layout) : std::string()) +
               "; valid keys here: " + join(allowed),
           fallback_line_);
    entries_.push_back({k, {kn, it->second}});
  }
}

std::optional<YAML::Node> MapView::find(const std::string& k) const {
  for (const auto& e : entries_)
    if (e.first == k) return e.second.second;
  return std::nullopt;
}

YAML::Node MapView::require(const std::string& k) const {
  if (auto n = find(k)) return *n;
  fail(src_, node_, key(k), "missing required key", fallback_line_);
}

void MapView::warn_at(const YAML::Node& at, const std::string& k, const std::string& msg) const {
  const auto [file, line] = value_origin(src_, at, key(k), fallback_line_);
  warn(InputError::format(file, line, 0, "", msg));
}

void MapView::fail_at(const YAML::Node& at, const std::string& k, const std::string& msg) const {
  // An empty value's Mark points past it (to the next token): name the key's line instead.
  if (!at.IsDefined() || at.IsNull())
    for (const auto& e : entries_)
      if (e.first == k && e.second.second.is(at)) fail(src_, e.second.first, key(k), msg, fallback_line_);
  fail(src_, at, key(k), msg, fallback_line_);
}

double MapView::number(const YAML::Node& n, const std::string& k, const char* unit) const {
  const std::string in_unit = unit ? std::string(" in SI units (") + unit + ")" : std::string();
  if (!n.IsDefined() || n.IsNull()) fail_at(n, k, "missing value (expected a number" + in_unit + ")");
  if (!n.IsScalar()) fail_at(n, k, "expected a number" + in_unit + ", got " + node_kind(n));
  double v = 0;
  switch (parse_double(n.Scalar(), v)) {
    case NumberParse::ok:
      return v;
    case NumberParse::has_unit:
      fail_at(n, k,
              std::string("expected a plain number") + (unit ? in_unit : " (dimensionless)") + ", got " +
                  quote(n.Scalar()));
    case NumberParse::not_finite:
      fail_at(n, k, "must be a finite number, got " + quote(n.Scalar()));
    default:
      fail_at(n, k, "expected a number" + in_unit + ", got " + quote(n.Scalar()));
  }
}

int MapView::integer(const YAML::Node& n, const std::string& k) const {
  if (!n.IsDefined() || n.IsNull()) fail_at(n, k, "missing value (expected an integer)");
  int v = 0;
  if (!n.IsScalar() || !parse_int(n.Scalar(), v)) fail_at(n, k, "expected an integer, got " + node_kind(n));
  return v;
}

std::uint64_t MapView::seed(const YAML::Node& n, const std::string& k) const {
  if (!n.IsScalar()) fail_at(n, k, "expected a non-negative integer seed, got " + node_kind(n));
  const std::string s(trim(n.Scalar()));
  std::uint64_t v = 0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || p != s.data() + s.size())
    fail_at(n, k, "expected a non-negative integer seed below 2^64, got " + quote(s));
  return v;
}

bool MapView::boolean(const YAML::Node& n, const std::string& k) const {
  if (!n.IsDefined() || n.IsNull()) fail_at(n, k, "missing value (expected true or false)");
  if (n.IsScalar()) {
    const std::string s(trim(n.Scalar()));
    if (s == "true" || s == "True" || s == "TRUE") return true;
    if (s == "false" || s == "False" || s == "FALSE") return false;
  }
  fail_at(n, k, "expected true or false, got " + node_kind(n));
}

std::string MapView::string(const YAML::Node& n, const std::string& k) const {
  if (!n.IsDefined() || n.IsNull()) fail_at(n, k, "missing value (expected text)");
  if (!n.IsScalar()) fail_at(n, k, "expected text, got " + node_kind(n));
  return n.Scalar();
}

std::vector<std::string> MapView::string_list(const YAML::Node& n, const std::string& k) const {
  if (!n.IsDefined() || n.IsNull()) fail_at(n, k, "missing value (expected a list such as [t, Q, A])");
  if (!n.IsSequence()) fail_at(n, k, "expected a list such as [t, Q, A], got " + node_kind(n));
  std::vector<std::string> out;
  for (const auto& c : n) {
    if (!c.IsScalar())
      fail(src_, c.Mark().is_null() ? n : c, key(k), "list items must be names, got " + node_kind(c), fallback_line_);
    out.push_back(c.Scalar());
  }
  return out;
}

// A double-quoted YAML scalar with escapes (the one quoting used for every file we write).
std::string yaml_quoted(const std::string& s) {
  static const char* hex = "0123456789ABCDEF";
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (c < 0x20 || c == 0x7F) {
          out += "\\x";
          out += hex[c >> 4];
          out += hex[c & 0xF];
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

}  // namespace asperity::io
