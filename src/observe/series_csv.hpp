#pragma once
// series.csv, the sampled series of one run (a run folder's series.csv; the rows of a point's block
// in a campaign store's series.csv): a header of the chosen columns in all_series() order (t, X, V, Q, A,
// n_slipping, n_intact), then one row per sample, reals as %.17g (exact round trip), counts as
// integers.
#include <ostream>
#include <string>
#include <vector>

#include "solve/core/observer.hpp"

namespace asperity {

// Writes `series` columns (validated against all_series(), written in its order) of `samples`.
// Throws std::invalid_argument on an unknown column name.
void write_series_csv(std::ostream& out, const std::vector<Sample>& samples, const std::vector<std::string>& series);

}  // namespace asperity
