#include "studies/topography_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <utility>

#include "io/csv.hpp"
#include "io/input_error.hpp"
#include "io/numbers.hpp"

namespace asperity {

std::vector<TopographyShapeRow> read_topography_table(const std::filesystem::path& file) {
  // A results table: far below this; the cap keeps a wrong file from exhausting memory.
  const io::TextTable t = io::read_text_table(file, file.generic_string(), 100000);
  std::vector<TopographyShapeRow> rows;
  if (t.columns.empty()) return rows;
  for (const char* name :
       {"seed", "P_N", "N", "model", "alpha_b", "n", "endpoint_residual", "residual_rms_m2", "noise_rms_p95_m2"})
    t.column(name);  // every column present, rows or not
  for (std::size_t i = 0; i < t.size(); ++i) {
    auto number = [&](const char* name) { return t.number(i, name); };
    TopographyShapeRow r;
    r.seed = static_cast<int>(number("seed"));
    r.load_N = number("P_N");
    r.junctions = static_cast<int>(number("N"));
    r.model = t.text(i, "model");
    if (r.model != "independent" && r.model != "interacting")
      t.fail(i, "model", "'" + r.model + "' is neither independent nor interacting");
    r.alpha_b = number("alpha_b");
    r.shape_exponent = number("n");
    r.endpoint_residual = number("endpoint_residual");
    r.residual_rms_m2 = number("residual_rms_m2");
    r.noise_rms_p95_m2 = number("noise_rms_p95_m2");
    rows.push_back(std::move(r));
  }
  return rows;
}

TopographyTally tally_topography(const std::vector<TopographyShapeRow>& rows) {
  TopographyTally t;
  std::map<std::pair<int, double>, std::pair<const TopographyShapeRow*, const TopographyShapeRow*>> by_load;
  for (const TopographyShapeRow& r : rows) {
    ++t.rows;
    if (r.within_noise()) ++t.within_noise;
    auto& p = by_load[{r.seed, r.load_N}];
    (r.model == "independent" ? p.first : p.second) = &r;
  }
  double sum = 0;
  for (const auto& [key, p] : by_load) {
    if (!p.first || !p.second) continue;
    const double dn = p.second->shape_exponent - p.first->shape_exponent;
    t.min_dn = t.pairs == 0 ? dn : std::min(t.min_dn, dn);
    t.max_dn = t.pairs == 0 ? dn : std::max(t.max_dn, dn);
    sum += dn;
    if (dn < 0) ++t.n_lower;
    t.max_abs_dres = std::max(t.max_abs_dres, std::abs(p.second->endpoint_residual - p.first->endpoint_residual));
    ++t.pairs;
  }
  t.mean_dn = t.pairs > 0 ? sum / t.pairs : NAN;
  return t;
}

}  // namespace asperity
