#pragma once
// What a sweep store records of how its points were computed, and the checks of it that a run
// makes (sweep.cpp runs the points): the folder a store may be, provenance.yaml and campaign.yaml
// written when the store is started, the fingerprint of the inputs in inputs.txt, whether each
// stored point's scene hash is still the one its point gives, and the bookkeeping after a run
// (points.csv current, series.csv compacted). Internal to campaign/.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "campaign/sweep.hpp"

namespace asperity {
class ParallelRunner;  // batch/parallel_runner.hpp
}  // namespace asperity

namespace asperity::sweep_detail {

// `--out .` or a typo must not write store files among unrelated ones (points.csv would be
// replaced): an existing folder may hold only what a store holds (a run killed at its start may
// have left some of it), including our temporary files (".NAME.tmp-*") and figures.
void check_store_folder(const std::filesystem::path& dir);

// Checks a resumed store was started from the same campaign text and deals its points as asked;
// starts a new one otherwise. Returns the store's balance.
ShardBalance prepare_store(const std::filesystem::path& dir, const Campaign& c, const SweepOptions& opt);

// DIR/inputs.txt (batch/inputs_fingerprint.hpp) but its last line: what the stored points'
// hashes were last all checked against (see SweepOptions::build_id). The next run recomputes this
// text from the files it lists and trusts the stored hashes when it comes out the same.
std::string inputs_text(const Campaign& c, const std::string& build_id, const ShardPlan& plan,
                        const std::vector<std::filesystem::path>& files, FileHashes& hashes);

// inputs.txt ends with the SHA-256 of points.csv as written with it: "points.csv sha256 HEX".
inline const std::string kPointsDigestTag = "points.csv sha256 ";

// Cuts that last line off `text` (what inputs_text recomputes is compared without it) and returns
// its digest; empty when there is none.
std::string take_points_digest(std::string& text);

// The files listed by DIR/inputs.txt (absolute), or nothing when it is absent or not ours.
std::vector<std::filesystem::path> listed_inputs(const std::string& text, const Campaign& c);

// The scene hash of a stored row (its second field).
std::uint64_t row_hash(const std::string& row);

// Whether the stored hash of each entry of `stored` is the one its point's scene and data give
// now: every stored point of the shard rebuilt and hashed, in parallel (one scene builder per
// thread); `rehashed` counts them.
std::vector<std::uint8_t> recheck_stored(const Campaign& c, const SweepOptions& opt, const ShardPlan& shard,
                                         const Journal& journal, FileHashes& data_hashes, const ParallelRunner& runner,
                                         std::uint64_t& rehashed_out);

// series.csv without superseded blocks or blocks of points no longer ok (streamed rewrite; only
// when it holds any).
void compact_series(SeriesFile& series, const Journal& journal);

// Whether points.csv is known to be the journal's already: nothing appended or dropped now,
// inputs.txt was there (written only after points.csv at the end of a run, removed before a run
// appends anything) and unchanged, and points.csv still has the SHA-256 it was written with (a
// truncated or edited copy is rebuilt from the journal).
bool points_current(const SweepReport& rep, const std::string& points_digest);

}  // namespace asperity::sweep_detail
