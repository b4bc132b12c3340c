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

// "model.eta [1/s]", "model.epsilon [1]", or the column as is when its unit is unknown.
std::string axis_label(const std::string& column);

// docs/units.md: the unit of every column a result holds (scene keys, observables, series
// columns), from the same tables; a test keeps the committed file equal to it.
std::string units_reference_markdown();

}  // namespace asperity
