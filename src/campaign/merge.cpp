#include "campaign/merge.hpp"

#include <algorithm>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "campaign/store.hpp"
#include "campaign/sweep.hpp"  // kStoreProvenanceFirstLine
#include "io/journal_line.hpp"
#include "scene/load.hpp"

namespace asperity {
namespace fs = std::filesystem;

namespace {

std::string provenance_line(const std::string& text, const std::string& key) {
  const std::size_t at = text.find("\n" + key + ":");
  if (at == std::string::npos) return "";
  const std::size_t end = text.find('\n', at + 1);
  return text.substr(at + 1, end == std::string::npos ? std::string::npos : end - at - 1);
}

// One point found in two inputs: its identity (the scene hash, which covers the bytes of the
// junctions and measured CSVs) and, when both ran to the end, its values (wall_s aside) must
// agree; otherwise one of the stores is stale and merging would keep either silently.
void check_same_point(std::uint64_t index, const std::string& kept, const std::string& other, const fs::path& kept_in,
                      const fs::path& other_in, const std::string& header) {
  const auto a = io::csv_split(kept), b = io::csv_split(other);
  const auto names = io::csv_split(header);
  const std::string point =
      "merge: point " + std::to_string(index) + " (grid " + a.at(2) + ", experiment " + a.at(3) + ")";
  if (a.at(1) != b.at(1))
    throw std::runtime_error(point + " was computed from different scenes or data: hash " + a.at(1) + " in " +
                             kept_in.string() + ", " + b.at(1) + " in " + other_in.string() +
                             " (the hash covers the scene and the bytes of its junctions and measured CSVs); "
                             "resume the stale store with asperity sweep --out, then merge");
  const std::size_t status = Journal::status_column(header);
  if (a.at(status) != "ok" || b.at(status) != "ok") return;
  for (std::size_t i = status + 2; i + 1 < names.size() && i + 1 < a.size(); ++i)  // observables; wall_s is last
    if (a.at(i) != b.at(i))
      throw std::runtime_error(point + ", hash " + a.at(1) + ": " + names.at(i) + " = " + a.at(i) + " in " +
                               kept_in.string() + " but " + b.at(i) + " in " + other_in.string() +
                               " (another build or machine?); merge stores computed by one build");
}

// The input stores, read-only (only their indexes are held: 16 bytes a row), after checking they
// share their columns and campaign text; `first_provenance`: the first input's provenance.yaml.
std::vector<StoreReader> open_inputs(const std::vector<fs::path>& inputs, std::string& header,
                                     std::string& first_provenance) {
  std::string campaign_hash;
  std::vector<StoreReader> stores;
  stores.reserve(inputs.size());
  for (const fs::path& in : inputs) {
    const StoreReader& s = stores.emplace_back(in);
    const std::string prov = io::read_file_text(in / "provenance.yaml");
    const std::string h = provenance_line(prov, "campaign_fnv1a64");
    if (header.empty()) {
      header = s.header(), campaign_hash = h, first_provenance = prov;
      continue;
    }
    if (s.header() != header)
      throw std::runtime_error("merge: " + in.string() + " has other columns than " + inputs[0].string());
    if (h != campaign_hash)
      throw std::runtime_error("merge: " + in.string() + " comes from another campaign text than " +
                               inputs[0].string() + " (" + h + " vs " + campaign_hash + ")");
  }
  return stores;
}

// Series files (series.csv) of the inputs that have one (null where none): one set of columns
// for all, whose header line is `series_header` (empty: no input has series).
std::vector<std::unique_ptr<SeriesFile>> open_input_series(const std::vector<fs::path>& inputs,
                                                           std::string& series_header) {
  std::vector<std::unique_ptr<SeriesFile>> series(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    if (!fs::exists(inputs[i] / "series.csv")) continue;
    series[i] = std::make_unique<SeriesFile>(inputs[i], false);
    std::string h = "index";
    for (const std::string& col : series[i]->columns()) h += "," + col;
    if (series_header.empty())
      series_header = h;
    else if (h != series_header)
      throw std::runtime_error("merge: " + (inputs[i] / "series.csv").string() + " has other series columns (" + h +
                               ") than the first input's (" + series_header + ")");
  }
  return series;
}

// Visits every point index once, ascending, with the inputs holding it (in input order), by
// walking the sorted indexes side by side: no index of the output is held.
void for_each_point(const std::vector<StoreReader>& stores,
                    const std::function<void(std::uint64_t, const std::vector<std::size_t>&)>& visit) {
  std::vector<std::size_t> pos(stores.size(), 0), holders;
  for (;;) {
    std::uint64_t next = 0;
    bool any = false;
    for (std::size_t i = 0; i < stores.size(); ++i)
      if (pos[i] < stores[i].rows().size() && (!any || stores[i].rows()[pos[i]].index < next))
        next = stores[i].rows()[pos[i]].index, any = true;
    if (!any) return;
    holders.clear();
    for (std::size_t i = 0; i < stores.size(); ++i)
      if (pos[i] < stores[i].rows().size() && stores[i].rows()[pos[i]].index == next) holders.push_back(i);
    visit(next, holders);
    for (const std::size_t i : holders) ++pos[i];
  }
}

// The row of point `index` in a store that holds it.
std::string row_of(const StoreReader& store, std::uint64_t index) {
  const auto r = store.rows();
  const auto it =
      std::lower_bound(r.begin(), r.end(), index, [](const StoredRow& e, std::uint64_t i) { return e.index < i; });
  return store.row(*it);
}

// Before anything is written: points held by more than one input must agree; the one kept is the
// first that ran to the end (only these choices are held, by point index).
std::map<std::uint64_t, std::size_t> choose_duplicates(const std::vector<StoreReader>& stores,
                                                       const std::vector<fs::path>& inputs, const std::string& header,
                                                       MergeReport& rep) {
  const std::size_t status_col = Journal::status_column(header);
  std::map<std::uint64_t, std::size_t> chosen;
  for_each_point(stores, [&](std::uint64_t index, const std::vector<std::size_t>& holders) {
    if (holders.size() < 2) return;
    std::size_t kept = holders[0];
    std::string kept_row = row_of(stores[kept], index);
    for (std::size_t k = 1; k < holders.size(); ++k) {
      ++rep.duplicates;
      const std::string row = row_of(stores[holders[k]], index);
      check_same_point(index, kept_row, row, inputs[kept], inputs[holders[k]], header);
      // Both agree (or one failed): keep a row that ran to the end.
      if (io::csv_split(kept_row).at(status_col) != "ok") kept = holders[k], kept_row = row;
    }
    chosen[index] = kept;
  });
  return chosen;
}

// Provenance of the first input, with its shard replaced by the list of merged stores.
std::string merged_provenance(const std::string& provenance, const std::vector<fs::path>& inputs) {
  std::string prov;
  for (std::size_t pos = 0; pos < provenance.size();) {
    const std::size_t nl = provenance.find('\n', pos);
    const std::string line = provenance.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos + 1);
    pos = nl == std::string::npos ? provenance.size() : nl + 1;
    if (line.rfind("shard_balance:", 0) == 0) continue;  // one store: nothing dealt
    if (line.rfind("shard:", 0) == 0) {
      prov += "shard: \"0/1\"  # merged\nmerged_from:\n";
      for (const fs::path& in : inputs) prov += "  - " + io::yaml_quoted(in.string()) + "\n";
    } else {
      prov += line;
    }
  }
  return prov;
}

// Stores written before series.csv hold series/HASH.csv per point: copied as they are.
void copy_legacy_series(const std::vector<fs::path>& inputs, const fs::path& out) {
  for (const fs::path& in : inputs)
    if (fs::is_directory(in / "series")) {
      fs::create_directories(out / "series");
      for (const auto& e : fs::directory_iterator(in / "series"))
        if (e.path().extension() == ".csv")
          fs::copy_file(e.path(), out / "series" / e.path().filename(), fs::copy_options::skip_existing);
    }
}

}  // namespace

MergeReport merge_stores(const std::vector<fs::path>& inputs, const fs::path& out) {
  if (inputs.empty()) throw std::runtime_error("merge: no input stores");
  if (fs::exists(out / "journal.csv"))
    throw std::runtime_error("merge: " + out.string() + " already holds a store; choose a new --out");
  MergeReport rep;
  std::string header, provenance, series_header;
  const std::vector<StoreReader> stores = open_inputs(inputs, header, provenance);
  const std::size_t status_col = Journal::status_column(header);
  const std::vector<std::unique_ptr<SeriesFile>> series = open_input_series(inputs, series_header);
  const std::map<std::uint64_t, std::size_t> chosen = choose_duplicates(stores, inputs, header, rep);
  fs::create_directories(out);
  StoreLock lock(out);
  io::remove_stale_temporaries(out);  // of a merge stopped by kill -9 or a lost node
  io::AtomicFileWriter journal(out / "journal.csv", io::Durability::synced),
      points(out / "points.csv", io::Durability::synced);
  journal.write(io::journal_header(header) + "\n");
  points.write(header + "\n");
  std::optional<io::AtomicFileWriter> series_out;
  if (!series_header.empty()) {
    series_out.emplace(out / "series.csv", io::Durability::synced);
    series_out->write(series_header + "\n");
  }
  for_each_point(stores, [&](std::uint64_t index, const std::vector<std::size_t>& holders) {
    const auto it = holders.size() > 1 ? chosen.find(index) : chosen.end();
    const std::size_t input = it != chosen.end() ? it->second : holders[0];
    const std::string row = row_of(stores[input], index);
    journal.write(io::journal_line(row));
    points.write(row + "\n");
    // The point's series block from the input whose row is kept, when it has the row's hash.
    if (series_out && series[input]) {
      const auto f = io::csv_split(row);
      const SeriesBlock* b = series[input]->find(index);
      if (b && io::hex16(b->hash) == f.at(1)) series_out->write(series_block(index, b->hash, series[input]->rows(*b)));
    }
    ++rep.rows;
    if (io::csv_split(row).at(status_col) != "ok") ++rep.failed;
  });
  // provenance.yaml first (merge_remnant knows the folder by it), journal.csv last (the merge is
  // done when it is there).
  io::write_file_durably(out / "provenance.yaml", merged_provenance(provenance, inputs));
  io::write_file_durably(out / "campaign.yaml", io::read_file_text(inputs[0] / "campaign.yaml"));
  copy_legacy_series(inputs, out);
  if (series_out) series_out->commit();
  points.commit();
  journal.commit();
  return rep;
}

bool merge_remnant(const fs::path& dir) {
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir / "journal.csv", ec))) return false;  // a store, merged or swept
  bool provenance = false;
  if (fs::is_regular_file(fs::symlink_status(dir / "provenance.yaml", ec))) {
    std::ifstream in(dir / "provenance.yaml");
    std::string first;
    provenance = std::getline(in, first) && first == kStoreProvenanceFirstLine;
  }
  static const std::string_view written[] = {"provenance.yaml", "campaign.yaml", "series", "series.csv", "points.csv"};
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    const bool temporary =
        n[0] == '.' && (n.find(".tmp-") != std::string::npos || n.find(".old-") != std::string::npos);
    if (n == ".lock" || temporary) continue;
    if (provenance && std::find(std::begin(written), std::end(written), n) != std::end(written)) continue;
    return false;
  }
  return !ec;
}

}  // namespace asperity
