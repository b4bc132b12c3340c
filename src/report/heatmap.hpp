#pragma once
// Heat map (PNG, gnuplot) of one column of a sweep store over two of its columns.
#include <filesystem>
#include <string>
#include <vector>

namespace asperity {

struct HeatmapOptions {
  std::string x, y, z;             // column names (varied keys or observables)
  std::vector<std::string> where;  // "column=value" filters (numbers compare by value)
  std::filesystem::path out;       // empty: STORE/heatmap_<z>_over_<x>_<y>.png
};

struct HeatmapReport {
  std::filesystem::path png;
  std::size_t cells = 0, blank = 0;  // blank: NaN (e.g. no stick-slip), failed or missing
  std::string used_grid;             // the grid picked automatically (empty: all rows)
};

// Reads the store's journal (so a running or interrupted store can be plotted). Cells are laid
// out by rank of the distinct x and y values (irregular axes such as eta ∈ {0, 50, ..., 180,
// 200, 250} stay readable), labelled with the exact values. When several grids hold the x and y
// columns, the rows of the grids that vary both are used. Cells that still hold several points
// (e.g. six experiments) → InputError naming the columns to filter with --where.
// Bad column names or filters → InputError; gnuplot missing or failing → std::runtime_error.
HeatmapReport plot_heatmap(const std::filesystem::path& store, const HeatmapOptions& options);

}  // namespace asperity
