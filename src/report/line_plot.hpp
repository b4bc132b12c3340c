#pragma once
// Line plot of one column of a sweep store over one axis, one line per experiment (a 1-D grid,
// or a slice of a larger one chosen with --where).
#include <filesystem>
#include <string>
#include <vector>

namespace asperity {

struct LinePlotOptions {
  std::string x, y;                // columns: the axis (a varied key) and the value (an observable)
  std::vector<std::string> where;  // "column=value" filters
  std::filesystem::path out;       // empty: STORE/line_<y>_over_<x>.png; .png, .svg or .pdf
};

struct LinePlotReport {
  std::filesystem::path figure;
  std::size_t lines = 0, points = 0, blank = 0;  // blank: NaN, failed or missing
  std::string used_grid;                         // grids that vary x, when not all do
};

// Reads the store's journal; rows of the grids that vary x when some do not. Two points of one
// experiment at the same x that differ elsewhere → InputError naming the column to filter with
// --where. Log x axis for logspace values (plot_axes.hpp). gnuplot missing or failing →
// std::runtime_error (the script is kept beside the figure).
LinePlotReport plot_lines(const std::filesystem::path& store, const LinePlotOptions& options);

}  // namespace asperity
