#pragma once
// Merges stores of one campaign (typically its shards, run with --shard I/N on several machines)
// into one store, equal to the store an unsharded run writes (wall times aside).
#include <cstdint>
#include <filesystem>
#include <vector>

namespace asperity {

struct MergeReport {
  std::uint64_t rows = 0, failed = 0, duplicates = 0;  // duplicates: same point in two inputs
};

// Reads the journals of `inputs` (torn lines ignored), checks they come from the same campaign
// text and store format, and writes `out` (journal.csv, points.csv, provenance.yaml with the
// list of inputs, campaign.yaml, series.csv with the block of each point whose row is kept,
// and the per-point files series/HASH.csv of stores written before series.csv). Throws std::runtime_error, before writing anything, on
// a mismatch, on one point stored with two different scene hashes (the hash covers the bytes of
// the junctions and measured CSVs: one store is stale) or with two different values, or when
// `out` already holds a store. A point that failed in one input and ran in another keeps the
// row that ran. journal.csv is written last: until it is there the merge is not done (and a rerun
// may write `out` again, merge_remnant). The merged store can be resumed by `asperity sweep --out OUT` to fill gaps.
MergeReport merge_stores(const std::vector<std::filesystem::path>& inputs, const std::filesystem::path& out);

// Whether `dir` holds only what a stopped or failed merge (a signal, a full disk) leaves there: its
// lock, asperity's temporaries (".NAME.tmp-*"), and the files a merge writes before the journal
// that completes it (provenance.yaml first, with a store's first line, then campaign.yaml,
// series/, series.csv, points.csv). A rerun writes there: merge_stores removes the temporaries
// and replaces the rest.
bool merge_remnant(const std::filesystem::path& dir);

}  // namespace asperity
