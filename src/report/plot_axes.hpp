#pragma once
// What the store plots (heat maps, line plots) share: reading store values, numeric axes (log
// scale where the values call for it, cell edges, tics at the values, labels with units), and
// the rule for which existing figure a plot may replace.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace asperity::plot_detail {

// The rows of a store (its journal, so a running store plots) kept by --where filters
// ("column=value", numbers compared by value). Unknown columns → InputError naming the option.
struct StoreTable {
  StoreTable(const std::filesystem::path& store, const std::vector<std::string>& where);
  std::size_t column(const std::string& name, const char* option) const;
  // The kept rows whose columns `numeric` all hold finite numbers.
  std::vector<std::vector<std::string>> rows_with_numbers(const std::vector<std::size_t>& numeric) const;

  std::filesystem::path store;
  std::string header;
  std::vector<std::string> cols;
  std::vector<std::vector<std::string>> rows;  // after the filters, in index order
};

// A store text as a number ("nan", "inf" included); false when it is not one.
bool number_of(const std::string& s, double& x);
// Equal texts, or equal numbers (so --where model.eta=100 matches "100" and "1e2").
bool same_value(const std::string& a, const std::string& b);
// A column name made safe for a file name.
std::string file_part(std::string s);
// Sorted distinct values of a column (numerically), as their store texts.
std::vector<std::string> distinct_sorted(const std::vector<std::vector<std::string>>& rows, std::size_t col);

// The figure a plot may write: --out must name a .png, .svg or .pdf file; an existing file is
// replaced only when asperity drew it (png_is_ours) or, inside the store folder, when it is a
// PNG (heat maps drawn before the tag existed, e.g. the committed ones). InputError otherwise.
void check_png_target(const std::filesystem::path& figure, const std::filesystem::path& store, bool from_out);

// Keeps, when some grids vary every one of `columns` and others do not, only the rows of those
// that do (a one-at-a-time grid would pile up at its base values otherwise); returns their
// names, comma-separated ("" when every row was kept).
std::string keep_grids_varying(std::vector<std::vector<std::string>>& rows, std::size_t grid_column,
                               const std::vector<std::size_t>& columns);

// Whether the store ran on stand-in experiments (its provenance.yaml says stand_in_data: true):
// its figures carry the stand-in mark.
bool store_is_stand_in(const std::filesystem::path& store);

// The --where filters as a title says them (enhanced text), each after ", ": the physics, not
// the store's key names: "model.eta=100" → "η = 100", "experiment=P4.00N" → "P4.00N"; a grid
// filter (grid=alpha_b, which one-at-a-time grid of the campaign) is left out: the axes say what
// varies. A column without a symbol prints as typed.
std::string where_title(const std::vector<std::string>& where);

// Whether an axis reads better on a log scale: positive values that are geometrically spaced
// (three or more, equal ratios to 1e-6 and not equally spaced, as `logspace` makes them) or
// that span two decades or more (e.g. c_min ∈ {1e-5, 1e-2}).
bool log_axis(const std::vector<double>& sorted_values);

// Cell edges around sorted distinct values: midpoints between neighbours (in log10 on a log
// axis); an outer cell reaches as far out as its inner half gap (±0.5, or ±0.5 decade, alone).
std::vector<std::pair<double, double>> cell_edges(const std::vector<double>& sorted_values, bool log);

// gnuplot settings of a numeric axis ("x" or "y"): the label with its unit, log scale when
// `log`, tics at the values (their store texts) when there are at most 12, labelled where the
// labels clear each other at a journal column's width (the others unlabelled; more than eight x
// labels rotated by 60°), the range `edges`
// span (none when `edges` is empty). Values and edges are in the column's figure unit
// (figure_unit: the store's SI value times its scale).
std::string axis_settings(const char* axis, const std::string& column, const std::vector<std::string>& texts,
                          const std::vector<std::pair<double, double>>& edges, bool log);

}  // namespace asperity::plot_detail
