#include "campaign/export_sqlite.hpp"

#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "campaign/store.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"
#include "io/temp_files.hpp"
#include "observe/observables.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

enum class Type { integer, real, flag, text };

const char* sql_type(Type t) {
  switch (t) {
    case Type::integer:
    case Type::flag: return "INTEGER";
    case Type::real: return "REAL";
    case Type::text: return "TEXT";
  }
  return "TEXT";
}

std::string quoted_name(const std::string& name) {  // an SQL identifier
  std::string q = "\"";
  for (const char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// A store number: finite text, or nan/inf (the store writes non-finite values so).
bool store_number(const std::string& s, double& x) {
  if (s == "nan" || s == "inf" || s == "-inf") {
    x = s == "nan" ? NAN : (s == "inf" ? INFINITY : -INFINITY);
    return true;
  }
  return scene_io::parse_double(s, x) == scene_io::NumberParse::ok;
}

class Db {
 public:
  explicit Db(const fs::path& file) {
    if (sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
      const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      throw std::runtime_error("cannot create " + file.string() + ": " + why);
    }
  }
  ~Db() {
    for (sqlite3_stmt* st : statements_) sqlite3_finalize(st);
    sqlite3_close(db_);
  }
  Db(const Db&) = delete;
  Db& operator=(const Db&) = delete;
  void exec(const std::string& sql) {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
      const std::string why = err ? err : "?";
      sqlite3_free(err);
      throw std::runtime_error("sqlite: " + why + " in: " + sql.substr(0, 200));
    }
  }
  sqlite3_stmt* prepare(const std::string& sql) {
    sqlite3_stmt* st = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &st, nullptr) != SQLITE_OK)
      throw std::runtime_error(std::string("sqlite: ") + sqlite3_errmsg(db_));
    statements_.push_back(st);
    return st;
  }
  void step_reset(sqlite3_stmt* st) {
    if (sqlite3_step(st) != SQLITE_DONE) throw std::runtime_error(std::string("sqlite: ") + sqlite3_errmsg(db_));
    sqlite3_reset(st);
    sqlite3_clear_bindings(st);
  }
  void close() {
    for (sqlite3_stmt* st : statements_) sqlite3_finalize(st);
    statements_.clear();
    if (sqlite3_close(db_) != SQLITE_OK) throw std::runtime_error(std::string("sqlite: ") + sqlite3_errmsg(db_));
    db_ = nullptr;
  }

 private:
  sqlite3* db_ = nullptr;
  std::vector<sqlite3_stmt*> statements_;
};

// Removes the temporary database unless released.
struct TempFile {
  fs::path path;
  bool keep = false;
  ~TempFile() {
    if (!keep) ::unlink(path.c_str());
  }
};

}  // namespace

SqliteExportReport export_sqlite(const fs::path& store, const fs::path& file) {
  if (fs::exists(fs::symlink_status(file)))
    throw InputError(file.string(), 0, "--sqlite", "exists; export writes a new file only (choose another name)");
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  if (!fs::is_directory(folder))
    throw InputError(file.string(), 0, "--sqlite",
                     "its folder " + folder.string() + " does not exist (export writes a file, it makes no folders)");
  const StoreReader s(store);
  const std::vector<std::string> names = csv_split(s.header());
  const std::string where = fs::exists(store / "journal.csv") ? (store / "journal.csv").string() : (store / "points.csv").string();
  const bool has_status = std::find(names.begin(), names.end(), "status") != names.end();
  const std::size_t status = has_status ? Journal::status_column(s.header()) : 0;
  if (status < 4 || names.size() < 4 || names[0] != "index" || names[1] != "hash")
    throw InputError(where, 1, "", "not a sweep store header: " + s.header().substr(0, 80));

  // Column types: the fixed columns and observables by what they are; a varied key REAL when
  // every value of it is a number (first pass over the rows), TEXT otherwise.
  std::vector<Type> types(names.size(), Type::text);
  types[0] = Type::integer;
  std::vector<std::size_t> varied;
  for (std::size_t c = 4; c < status; ++c) varied.push_back(c), types[c] = Type::real;
  for (std::size_t c = status + 2; c < names.size(); ++c) {
    types[c] = Type::real;  // wall_s and any observable not in the table
    for (const ObservableField& f : observable_fields())
      if (names[c] == f.name)
        types[c] = f.kind == ObservableKind::real ? Type::real
                   : f.kind == ObservableKind::count ? Type::integer
                   : f.kind == ObservableKind::flag ? Type::flag
                                                    : Type::text;
  }
  if (!varied.empty())
    for (const StoredRow& r : s.rows()) {
      const std::vector<std::string> f = csv_split(s.row(r));
      for (const std::size_t c : varied) {
        double x = 0;
        if (types[c] == Type::real && c < f.size() && !f[c].empty() && !store_number(f[c], x)) types[c] = Type::text;
      }
    }
  // Unique column names (an `experiment` axis repeats the experiment column): NAME_2, NAME_3.
  std::vector<std::string> cols = names;
  for (std::size_t c = 0; c < cols.size(); ++c) {
    auto taken = [&](const std::string& n) { return std::find(cols.begin(), cols.begin() + static_cast<std::ptrdiff_t>(c), n) != cols.begin() + static_cast<std::ptrdiff_t>(c); };
    for (std::size_t k = 2; taken(cols[c]); ++k) cols[c] = names[c] + "_" + std::to_string(k);
  }

  std::string tmp_name = ".";
  tmp_name += file.filename().string();
  tmp_name += ".tmp-";
  tmp_name += unique_tmp_suffix();
  const fs::path tmp = file.parent_path() / tmp_name;
  TempFile guard{tmp};
  const TempGuard on_signal(tmp);
  SqliteExportReport rep;
  rep.columns = cols.size();
  {
    Db db(tmp);
    // A new file published only when complete: no rollback journal needed, no fsync per step.
    db.exec("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF;");
    std::string create = "CREATE TABLE points (";
    for (std::size_t c = 0; c < cols.size(); ++c)
      create += (c ? ", " : "") + quoted_name(cols[c]) + " " + sql_type(types[c]) + (c == 0 ? " PRIMARY KEY" : "");
    db.exec(create + ")");
    db.exec("CREATE TABLE store_files (name TEXT PRIMARY KEY, text TEXT)");
    db.exec("BEGIN");
    std::string insert = "INSERT INTO points VALUES (";
    for (std::size_t c = 0; c < cols.size(); ++c) insert += c ? ", ?" : "?";
    sqlite3_stmt* st = db.prepare(insert + ")");
    for (const StoredRow& r : s.rows()) {
      const std::vector<std::string> f = csv_split(s.row(r));
      if (f.size() != cols.size())
        throw std::runtime_error(where + ": point " + std::to_string(r.index) + ": " + std::to_string(f.size()) +
                                 " fields, the header has " + std::to_string(cols.size()));
      for (std::size_t c = 0; c < cols.size(); ++c) {
        const int at = static_cast<int>(c) + 1;
        const std::string& v = f[c];
        auto bad = [&](const char* what) {
          return std::runtime_error(where + ": point " + std::to_string(r.index) + ": " + names[c] + ": " + what + " '" +
                                    v.substr(0, 40) + "'");
        };
        if (types[c] == Type::text) {
          sqlite3_bind_text(st, at, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
        } else if (v.empty() || v == "nan") {
          sqlite3_bind_null(st, at);
        } else if (types[c] == Type::flag) {
          if (v != "true" && v != "false") throw bad("not true/false");
          sqlite3_bind_int(st, at, v == "true" ? 1 : 0);
        } else if (types[c] == Type::integer) {
          std::int64_t n = 0;
          const auto p = std::from_chars(v.data(), v.data() + v.size(), n);
          if (p.ec != std::errc() || p.ptr != v.data() + v.size()) throw bad("not an integer");
          sqlite3_bind_int64(st, at, n);
        } else {
          double x = 0;
          if (!store_number(v, x)) throw bad("not a number");
          sqlite3_bind_double(st, at, x);
        }
      }
      db.step_reset(st);
      ++rep.rows;
    }
    sqlite3_stmt* files = db.prepare("INSERT INTO store_files VALUES (?, ?)");
    for (const std::string name : {"provenance.yaml", "campaign.yaml"}) {
      if (!fs::exists(store / name)) continue;
      const std::string text = read_file_text(store / name);
      sqlite3_bind_text(files, 1, name.data(), static_cast<int>(name.size()), SQLITE_TRANSIENT);
      sqlite3_bind_text(files, 2, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
      db.step_reset(files);
    }
    db.exec("COMMIT");
    for (std::size_t k = 0; k < varied.size(); ++k, ++rep.indexes)
      db.exec("CREATE INDEX points_by_" + std::to_string(k + 1) + " ON points (" + quoted_name(cols[varied[k]]) + ")");
    db.close();
  }
  // Published without ever replacing a file: link() fails when FILE exists.
  if (::link(tmp.c_str(), file.c_str()) != 0) {
    const int e = errno;
    throw std::runtime_error(e == EEXIST ? file.string() + " appeared while exporting; not overwritten"
                                         : "cannot create " + file.string() + ": " + std::strerror(e));
  }
  return rep;
}

}  // namespace asperity
