#pragma once
// A sweep store as an SQLite database (`asperity export STORE --sqlite FILE`): the rows of its
// points.csv (read from the journal, as StoreReader gives them: one per point, latest wins) in a
// table `points` with typed columns, named as in points.csv:
//   index INTEGER (the primary key), hash grid experiment status error TEXT,
//   each varied key REAL when every value of it in the store is a number, TEXT otherwise,
//   each observable by its kind: real REAL, count INTEGER, flag INTEGER (0/1), label TEXT,
//   wall_s REAL;
// an empty or `nan` number is NULL. One index per varied key (points_by_<n>, n = its position
// among the varied keys), so `WHERE "model.eta" = 100` does not scan the table. A table
// `store_files(name, text)` holds the store's provenance.yaml and campaign.yaml.
// FILE is never overwritten: an existing FILE is refused before anything is read, and the
// database is built in a temporary sibling that is hard-linked to FILE (which fails, and removes
// the temporary, if FILE appeared meanwhile).
#include <cstdint>
#include <filesystem>

namespace asperity {

struct SqliteExportReport {
  std::uint64_t rows = 0;
  std::size_t columns = 0, indexes = 0;
};

// std::runtime_error (one line) when STORE is not a store, FILE exists, or a typed column holds a
// value that is not its type (naming the store file, the point index and the column).
SqliteExportReport export_sqlite(const std::filesystem::path& store, const std::filesystem::path& file);

}  // namespace asperity
