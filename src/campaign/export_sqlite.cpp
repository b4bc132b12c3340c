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
    case Type::flag:
      return "INTEGER";
    case Type::real:
      return "REAL";
    case Type::text:
      return "TEXT";
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
  return io::parse_double(s, x) == io::NumberParse::ok;
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

// FILE must be new, in a folder that exists (export makes no folders, replaces no file).
void check_export_target(const fs::path& file) {
  if (fs::exists(fs::symlink_status(file)))
    throw io::InputError(file.string(), 0, "--sqlite", "exists; export writes a new file only (choose another name)");
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  if (!fs::is_directory(folder))
    throw io::InputError(
        file.string(), 0, "--sqlite",
        "its folder " + folder.string() + " does not exist (export writes a file, it makes no folders)");
}

// The store's columns as the table holds them, and where its rows are read from (for messages).
struct ExportColumns {
  std::vector<std::string> names, cols;  // as in the store; unique in the table (NAME_2, NAME_3)
  std::vector<Type> types;
  std::vector<std::size_t> varied;  // the varied keys' columns (indexed)
  std::string where;
};

// Column types: the fixed columns and observables by what they are; a varied key REAL when every
// value of it is a number (a first pass over the rows), TEXT otherwise.
void set_column_types(const StoreReader& s, std::size_t status, ExportColumns& x) {
  x.types.assign(x.names.size(), Type::text);
  x.types[0] = Type::integer;
  for (std::size_t c = 4; c < status; ++c) x.varied.push_back(c), x.types[c] = Type::real;
  for (std::size_t c = status + 2; c < x.names.size(); ++c) {
    x.types[c] = Type::real;  // wall_s and any observable not in the table
    for (const ObservableField& f : observable_fields())
      if (x.names[c] == f.name)
        x.types[c] = f.kind == ObservableKind::real    ? Type::real
                     : f.kind == ObservableKind::count ? Type::integer
                     : f.kind == ObservableKind::flag  ? Type::flag
                                                       : Type::text;
  }
  if (x.varied.empty()) return;
  for (const StoredRow& r : s.rows()) {
    const std::vector<std::string> f = io::csv_split(s.row(r));
    for (const std::size_t c : x.varied) {
      double v = 0;
      if (x.types[c] == Type::real && c < f.size() && !f[c].empty() && !store_number(f[c], v)) x.types[c] = Type::text;
    }
  }
}

ExportColumns export_columns(const StoreReader& s, const fs::path& store) {
  ExportColumns x;
  x.names = io::csv_split(s.header());
  x.where = fs::exists(store / "journal.csv") ? (store / "journal.csv").string() : (store / "points.csv").string();
  const bool has_status = std::find(x.names.begin(), x.names.end(), "status") != x.names.end();
  const std::size_t status = has_status ? Journal::status_column(s.header()) : 0;
  if (status < 4 || x.names.size() < 4 || x.names[0] != "index" || x.names[1] != "hash")
    throw io::InputError(x.where, 1, "", "not a sweep store header: " + s.header().substr(0, 80));
  set_column_types(s, status, x);
  // Unique column names (an `experiment` axis repeats the experiment column): NAME_2, NAME_3.
  x.cols = x.names;
  for (std::size_t c = 0; c < x.cols.size(); ++c) {
    auto taken = [&](const std::string& n) {
      return std::find(x.cols.begin(), x.cols.begin() + static_cast<std::ptrdiff_t>(c), n) !=
             x.cols.begin() + static_cast<std::ptrdiff_t>(c);
    };
    for (std::size_t k = 2; taken(x.cols[c]); ++k) x.cols[c] = x.names[c] + "_" + std::to_string(k);
  }
  return x;
}

// Binds the fields of the row of point `index` to the insert statement, each by its column's type.
void bind_row(sqlite3_stmt* st, const std::vector<std::string>& f, const ExportColumns& x, std::uint64_t index) {
  if (f.size() != x.cols.size())
    throw std::runtime_error(x.where + ": point " + std::to_string(index) + ": " + std::to_string(f.size()) +
                             " fields, the header has " + std::to_string(x.cols.size()));
  for (std::size_t c = 0; c < x.cols.size(); ++c) {
    const int at = static_cast<int>(c) + 1;
    const std::string& v = f[c];
    auto bad = [&](const char* what) {
      return std::runtime_error(x.where + ": point " + std::to_string(index) + ": " + x.names[c] + ": " + what + " '" +
                                v.substr(0, 40) + "'");
    };
    if (x.types[c] == Type::text) {
      sqlite3_bind_text(st, at, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    } else if (v.empty() || v == "nan") {
      sqlite3_bind_null(st, at);
    } else if (x.types[c] == Type::flag) {
      if (v != "true" && v != "false") throw bad("not true/false");
      sqlite3_bind_int(st, at, v == "true" ? 1 : 0);
    } else if (x.types[c] == Type::integer) {
      std::int64_t n = 0;
      const auto p = std::from_chars(v.data(), v.data() + v.size(), n);
      if (p.ec != std::errc() || p.ptr != v.data() + v.size()) throw bad("not an integer");
      sqlite3_bind_int64(st, at, n);
    } else {
      double d = 0;
      if (!store_number(v, d)) throw bad("not a number");
      sqlite3_bind_double(st, at, d);
    }
  }
}

// The database at `tmp`: the points table (one row per stored point), the store's text files,
// an index per varied key.
void write_database(const fs::path& tmp, const StoreReader& s, const fs::path& store, const ExportColumns& x,
                    SqliteExportReport& rep) {
  Db db(tmp);
  // A new file published only when complete: no rollback journal needed, no fsync per step.
  db.exec("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF;");
  std::string create = "CREATE TABLE points (";
  for (std::size_t c = 0; c < x.cols.size(); ++c)
    create += (c ? ", " : "") + quoted_name(x.cols[c]) + " " + sql_type(x.types[c]) + (c == 0 ? " PRIMARY KEY" : "");
  db.exec(create + ")");
  db.exec("CREATE TABLE store_files (name TEXT PRIMARY KEY, text TEXT)");
  db.exec("BEGIN");
  std::string insert = "INSERT INTO points VALUES (";
  for (std::size_t c = 0; c < x.cols.size(); ++c) insert += c ? ", ?" : "?";
  sqlite3_stmt* st = db.prepare(insert + ")");
  for (const StoredRow& r : s.rows()) {
    bind_row(st, io::csv_split(s.row(r)), x, r.index);
    db.step_reset(st);
    ++rep.rows;
  }
  sqlite3_stmt* files = db.prepare("INSERT INTO store_files VALUES (?, ?)");
  for (const std::string name : {"provenance.yaml", "campaign.yaml"}) {
    if (!fs::exists(store / name)) continue;
    const std::string text = io::read_file_text(store / name);
    sqlite3_bind_text(files, 1, name.data(), static_cast<int>(name.size()), SQLITE_TRANSIENT);
    sqlite3_bind_text(files, 2, text.data(), static_cast<int>(text.size()), SQLITE_TRANSIENT);
    db.step_reset(files);
  }
  db.exec("COMMIT");
  for (std::size_t k = 0; k < x.varied.size(); ++k, ++rep.indexes)
    db.exec("CREATE INDEX points_by_" + std::to_string(k + 1) + " ON points (" + quoted_name(x.cols[x.varied[k]]) +
            ")");
  db.close();
}

}  // namespace

SqliteExportReport export_sqlite(const fs::path& store, const fs::path& file) {
  check_export_target(file);
  const StoreReader s(store);
  const ExportColumns x = export_columns(s, store);
  const fs::path tmp = file.parent_path() / io::temp_name(file.filename().string());
  // An export killed before it could remove its temporary (kill -9, a lost node) left it here.
  io::remove_stale_temporaries(file.parent_path().empty() ? fs::path(".") : file.parent_path(),
                               io::temp_prefix(file.filename().string()));
  TempFile guard{tmp};
  const io::TempGuard on_signal(tmp);
  SqliteExportReport rep;
  rep.columns = x.cols.size();
  write_database(tmp, s, store, x, rep);
  // Published without ever replacing a file: link() fails when FILE exists.
  if (::link(tmp.c_str(), file.c_str()) != 0) {
    const int e = errno;
    throw std::runtime_error(e == EEXIST ? file.string() + " appeared while exporting; not overwritten"
                                         : "cannot create " + file.string() + ": " + std::strerror(e));
  }
  return rep;
}

}  // namespace asperity
