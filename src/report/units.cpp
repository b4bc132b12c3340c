#include "report/units.hpp"

#include "observe/observables.hpp"
#include "scene/scene_keys.hpp"

namespace asperity {

std::string column_unit(const std::string& column) {
  if (const SceneKey* k = find_scene_key(column)) {
    if (k->kind != KeyKind::number && k->kind != KeyKind::integer) return "";
    return k->unit ? k->unit : "1";
  }
  for (const ObservableField& f : observable_fields())
    if (column == f.name) {
      if (f.kind == ObservableKind::label || f.kind == ObservableKind::flag) return "";
      return *f.unit ? f.unit : "1";
    }
  return "";
}

std::string series_unit(const std::string& column) {
  static const char* const units[][2] = {{"t", "s"}, {"X", "m"}, {"V", "m/s"}, {"Q", "N"}, {"A", "m^2"},
                                          {"n_slipping", "1"}, {"n_intact", "1"}};
  for (const auto& [name, unit] : units)
    if (column == name) return unit;
  return "";
}

std::string axis_label(const std::string& column) {
  const std::string unit = column_unit(column);
  return unit.empty() ? column : column + " [" + unit + "]";
}

std::string units_reference_markdown() {
  std::string md =
      "# Units of every column\n\n"
      "Generated from the key and observable tables (`src/report/units.cpp`; `tests/test_report_units.cpp`\n"
      "keeps this file equal to them). All values are SI. `1`: dimensionless. Columns of a store's\n"
      "`points.csv`, of `summary.yaml`, `fitted.csv` and the bench CSVs are named as below; `table.csv`\n"
      "of `asperity reproduce` carries its units in its header names (`Q_s_N`, `A0_m2`, ...).\n\n"
      "## Scene keys (varied columns of a store, `--set`, fit parameters)\n\n| key | unit |\n|---|---|\n";
  for (const SceneKey& k : scene_keys()) {
    const std::string u = column_unit(k.name);
    if (!u.empty()) md += std::string("| `") + k.name + "` | " + u + " |\n";
  }
  md += "\n## Observables (summary.yaml, points.csv, fitted.csv)\n\n| column | unit |\n|---|---|\n";
  for (const ObservableField& f : observable_fields()) {
    const std::string u = column_unit(f.name);
    md += std::string("| `") + f.name + "` | " + (u.empty() ? std::string("(text or true/false)") : u) + " |\n";
  }
  md += "\n## Series (series.csv, a store's series)\n\n| column | unit |\n|---|---|\n";
  for (const std::string& c : all_series()) md += "| `" + c + "` | " + series_unit(c) + " |\n";
  return md;
}

}  // namespace asperity
