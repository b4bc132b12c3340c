#pragma once
// Units of the columns a result holds (scene keys from the key table, observables from the
// field table), for axis labels and for the units reference: one place per fact.
#include <string>

namespace asperity {

// SI unit of a scene key or observable column: "1/s", "N", ...; "1" when dimensionless; ""
// when the column is not a number we know (e.g. experiment, grid, status).
std::string column_unit(const std::string& column);

// SI unit of a series column (series.csv, a run's series): "s", "N", "1" for counts; "" when
// `column` is not one (scene/scene.hpp all_series).
std::string series_unit(const std::string& column);

// "model.eta [1/s]", "model.epsilon [1]", or the column as is when its unit is unknown (plain
// text: messages; figures use axis_markup).
std::string axis_label(const std::string& column);

// Figure labels, in gnuplot enhanced text (report/gnuplot.hpp), from the display table in
// units.cpp (the symbol is a figure's fact; the unit stays the key and field tables' one):
//   column_symbol("model.alpha_b") == "α_b", ("t_peak") == "t_{peak}"; a column the table does
//     not hold (experiment, a name from a store) prints as itself (enhanced_literal);
//   unit_markup("m^(2p+2)/N^2") == "m^{2p+2} N^{-2}", ("1/s") == "s^{-1}", ("N/m") == "N/m";
//   axis_markup("model.alpha_b") == "α_b [m^{2p+2} N^{-2}]", ("model.epsilon") == "ε [1]",
//     ("A0") == "A_0 [mm^2]" (figure_unit, below).
std::string column_symbol(const std::string& column);
bool has_column_symbol(const std::string& column);
std::string unit_markup(const std::string& unit);
std::string axis_markup(const std::string& column);

// The unit a figure shows a column in, and the factor from its SI value: SI, except contact
// areas (A, A0, A_s), shown in mm² (a contact of a few mm² reads as 2.5, not 2.5e-06), in the
// command-line and the Python figures alike:
//   figure_unit("A0") == {"mm^2", 1e6}, ("Q_s") == {"N", 1}, ("experiment") == {"", 1}.
// axis_markup gives a figure's label in this unit; a plot multiplies the values by `scale`.
struct FigureUnit {
  std::string unit;  // as column_unit writes units ("m^(2p+2)/N^2"; unit_markup for a figure)
  double scale = 1;
};
FigureUnit figure_unit(const std::string& column);

// docs/units.md: the unit of every column a result holds (scene keys, observables, series
// columns), from the same tables; a test keeps the committed file equal to it.
std::string units_reference_markdown();

}  // namespace asperity
