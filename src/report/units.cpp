#include "report/units.hpp"

#include <cctype>
#include <utility>

#include "observe/observables.hpp"
#include "report/gnuplot.hpp"
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
  static const char* const units[][2] = {{"t", "s"},   {"X", "m"},          {"V", "m/s"},     {"Q", "N"},
                                         {"A", "m^2"}, {"n_slipping", "1"}, {"n_intact", "1"}};
  for (const auto& [name, unit] : units)
    if (column == name) return unit;
  return "";
}

std::string axis_label(const std::string& column) {
  const std::string unit = column_unit(column);
  return unit.empty() ? column : column + " [" + unit + "]";
}

namespace {

// What a figure calls each numeric column (enhanced text): every number key of the scene key
// table, every real or count of the observable table, the series columns (a test checks that
// none is missing). A short word goes before a symbol the reader would not know.
const std::pair<const char*, const char*> kSymbols[] = {
    // scene keys
    {"experiment.mass", "M"},
    {"experiment.k_L", "k_L"},
    {"experiment.v", "v"},
    {"experiment.E", "E"},
    {"experiment.nu", "ν"},
    {"experiment.sigma_exp", "σ_{exp}"},
    {"model.eta", "η"},
    {"model.epsilon", "ε"},
    {"model.c_min", "c_{min}"},
    {"model.p", "p"},
    {"model.alpha_b", "α_b"},
    {"model.interaction_cutoff", "cutoff r_c"},
    {"model.position_scale", "position scale s"},
    {"solver.Ct", "C_t"},
    {"solver.tolerance", "tolerance"},
    {"solver.interaction_tolerance", "interaction tolerance"},
    {"stop.time", "t_{stop}"},
    {"stop.cycles", "stop after cycles"},
    {"stop.wall_time", "wall-time limit"},
    {"stop.max_slips", "slip limit"},
    {"output.every", "Δt_{out}"},
    {"output.peak_min_drop", "peak drop threshold"},
    {"topography.self_affine.seed", "surface seed"},
    {"topography.self_affine.hurst", "Hurst exponent H"},
    {"topography.self_affine.rms_height_m", "rms height h_{rms}"},
    {"topography.self_affine.rms_slope", "rms slope"},
    {"topography.sphere_radius_m", "sphere radius R"},
    {"topography.E", "E"},
    {"topography.nu", "ν"},
    {"topography.load_N", "load P"},
    // observables
    {"N", "junctions N"},
    {"A0", "A_0"},
    {"K0", "K_0"},
    {"T0", "T_0"},
    {"dt", "Δt"},
    {"Q_s", "Q_s"},
    {"A_s", "A_s"},
    {"t_peak", "t_{peak}"},
    {"alpha", "α"},
    {"alpha_R2", "R^2 of α"},
    {"alpha_points", "points of the α fit"},
    {"shape_exponent", "shape exponent n"},
    {"shape_prefactor", "shape prefactor c_n"},
    {"area_drop_fraction", "area drop 1 - A_s/A_0"},
    {"alpha_measured", "α_{meas}"},
    {"alpha_measured_R2", "R^2 of α_{meas}"},
    {"shape_exponent_measured", "shape exponent n_{meas}"},
    {"ss_cycles", "stick-slip cycles"},
    {"ss_drop", "stick-slip drop ΔQ_{ss}"},
    {"ss_period", "stick-slip period T_{ss}"},
    {"n_peaks", "peaks"},
    {"max_f_over_sigmaA", "max f_i/(σA_i)"},
    {"max_f_over_sigma_exp_A", "max f_i/(σ_{exp}A_i)"},
    {"t_end", "t_{end}"},
    {"steps", "steps"},
    {"rejected", "rejected steps"},
    {"force_evals", "force evaluations"},
    {"slips", "slips"},
    {"repins", "repins"},
    {"wall_s", "wall time"},
    // series columns
    {"t", "t"},
    {"X", "X"},
    {"V", "V"},
    {"Q", "Q"},
    {"A", "A"},
    {"n_slipping", "slipping junctions"},
    {"n_intact", "intact junctions"},
};

const char* find_symbol(const std::string& column) {
  for (const auto& [name, symbol] : kSymbols)
    if (column == name) return symbol;
  return nullptr;
}

// "m^(2p+2)" → "m^{2p+2}", "N^2" → "N^2", "m" → "m": one factor of a unit.
std::string factor_markup(const std::string& f, bool negate) {
  const std::size_t hat = f.find('^');
  std::string base = f.substr(0, hat), exponent = hat == std::string::npos ? "" : f.substr(hat + 1);
  if (exponent.size() >= 2 && exponent.front() == '(' && exponent.back() == ')')
    exponent = exponent.substr(1, exponent.size() - 2);
  if (negate) exponent.insert(0, exponent.empty() ? "-1" : "-");
  if (exponent.empty()) return enhanced_literal(base);
  const bool one_char = exponent.size() == 1;
  return enhanced_literal(base) + "^" + (one_char ? "" : "{") + enhanced_literal(exponent) + (one_char ? "" : "}");
}

}  // namespace

std::string column_symbol(const std::string& column) {
  const char* s = find_symbol(column);
  return s ? s : enhanced_literal(column);
}

bool has_column_symbol(const std::string& column) { return find_symbol(column) != nullptr; }

std::string unit_markup(const std::string& unit) {
  const std::size_t slash = unit.find('/');
  if (slash == std::string::npos) return factor_markup(unit, false);
  const std::string num = unit.substr(0, slash), den = unit.substr(slash + 1);
  // A plain denominator stays a fraction (N/m, m/s); one with a power, or over 1, becomes a
  // negative power (m^{2p+2} N^{-2}, s^{-1}).
  if (num == "1") return factor_markup(den, true);
  if (den.find('^') == std::string::npos) return factor_markup(num, false) + "/" + factor_markup(den, false);
  return factor_markup(num, false) + " " + factor_markup(den, true);
}

FigureUnit figure_unit(const std::string& column) {
  std::string unit = column_unit(column);
  if (unit.empty()) unit = series_unit(column);
  if (unit == "m^2" && (column == "A" || column == "A0" || column == "A_s")) return {"mm^2", 1e6};
  return {unit, 1};
}

std::string axis_markup(const std::string& column) {
  const std::string unit = figure_unit(column).unit;
  return unit.empty() ? column_symbol(column) : column_symbol(column) + " [" + unit_markup(unit) + "]";
}

std::string units_reference_markdown() {
  std::string md =
      "# Units of every column\n\n"
      "Generated from the key and observable tables (`src/report/units.cpp`; "
      "`tests/unit/report/test_report_units.cpp`\n"
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
