#include "campaign/merge.hpp"

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "campaign/store.hpp"
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
  const auto a = csv_split(kept), b = csv_split(other);
  const auto names = csv_split(header);
  const std::string point = "merge: point " + std::to_string(index) + " (grid " + a.at(2) + ", experiment " + a.at(3) + ")";
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

}  // namespace

MergeReport merge_stores(const std::vector<fs::path>& inputs, const fs::path& out) {
  if (inputs.empty()) throw std::runtime_error("merge: no input stores");
  if (fs::exists(out / "journal.csv"))
    throw std::runtime_error("merge: " + out.string() + " already holds a store; choose a new --out");
  MergeReport rep;
  std::string header, campaign_hash, provenance;
  // Only the index of each input is held (index → input, offset, length), never the rows' text:
  // memory does not grow with the rows.
  std::vector<StoreReader> stores;
  stores.reserve(inputs.size());
  struct Kept {
    std::size_t input;
    RowSpan span;
  };
  std::map<std::uint64_t, Kept> rows;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const fs::path& in = inputs[i];
    const StoreReader& s = stores.emplace_back(in);
    const std::string prov = read_file_text(in / "provenance.yaml");
    const std::string h = provenance_line(prov, "campaign_fnv1a64");
    if (header.empty()) {
      header = s.header(), campaign_hash = h, provenance = prov;
    } else {
      if (s.header() != header) throw std::runtime_error("merge: " + in.string() + " has other columns than " + inputs[0].string());
      if (h != campaign_hash)
        throw std::runtime_error("merge: " + in.string() + " comes from another campaign text than " + inputs[0].string() +
                                 " (" + h + " vs " + campaign_hash + ")");
    }
    const std::size_t status_col = Journal::status_column(header);
    for (const auto& [index, span] : s.rows()) {
      const auto [it, fresh] = rows.emplace(index, Kept{i, span});
      if (fresh) continue;
      ++rep.duplicates;
      const std::string kept = stores[it->second.input].row(it->second.span), row = s.row(span);
      check_same_point(index, kept, row, inputs[it->second.input], in, header);
      // Both agree (or one failed): keep a row that ran to the end.
      if (csv_split(kept).at(status_col) != "ok") it->second = Kept{i, span};
    }
  }
  fs::create_directories(out);
  StoreLock lock(out);
  const std::size_t status_col = Journal::status_column(header);
  AtomicFileWriter journal(out / "journal.csv", Durability::synced), points(out / "points.csv", Durability::synced);
  journal.write(header + ",check\n");
  points.write(header + "\n");
  for (const auto& [index, k] : rows) {
    const std::string row = stores[k.input].row(k.span);
    journal.write(row + "," + hex16(fnv1a64(row)) + "\n");
    points.write(row + "\n");
    ++rep.rows;
    if (csv_split(row).at(status_col) != "ok") ++rep.failed;
  }
  // Provenance of the first input, with its shard replaced by the list of merged stores.
  std::string prov;
  for (std::size_t pos = 0; pos < provenance.size();) {
    const std::size_t nl = provenance.find('\n', pos);
    const std::string line = provenance.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos + 1);
    pos = nl == std::string::npos ? provenance.size() : nl + 1;
    if (line.rfind("shard:", 0) == 0) {
      prov += "shard: \"0/1\"  # merged\nmerged_from:\n";
      for (const fs::path& in : inputs) prov += "  - " + yaml_quoted(in.string()) + "\n";
    } else {
      prov += line;
    }
  }
  write_file_durably(out / "campaign.yaml", read_file_text(inputs[0] / "campaign.yaml"));
  write_file_durably(out / "provenance.yaml", prov);
  for (const fs::path& in : inputs)
    if (fs::is_directory(in / "series")) {
      fs::create_directories(out / "series");
      for (const auto& e : fs::directory_iterator(in / "series"))
        if (e.path().extension() == ".csv")
          fs::copy_file(e.path(), out / "series" / e.path().filename(), fs::copy_options::skip_existing);
    }
  journal.commit();
  points.commit();
  return rep;
}

}  // namespace asperity
