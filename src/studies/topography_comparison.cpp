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
  const std::size_t c_seed = t.column("seed"), c_load = t.column("P_N"), c_n_junctions = t.column("N"),
                    c_model = t.column("model"), c_alpha = t.column("alpha_b"), c_n = t.column("n"),
                    c_end = t.column("endpoint_residual"), c_res = t.column("residual_rms_m2"),
                    c_noise = t.column("noise_rms_p95_m2");
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const std::vector<std::string>& f = t.rows[i];
    auto number = [&](std::size_t c) {
      double x = 0;
      if (io::parse_double(f[c], x) != io::NumberParse::ok || !std::isfinite(x))
        throw io::InputError(t.display, t.lines[i], t.columns[c], "not a finite number: '" + f[c] + "'",
                             static_cast<int>(c) + 1);
      return x;
    };
    TopographyShapeRow r;
    r.seed = static_cast<int>(number(c_seed));
    r.load_N = number(c_load);
    r.junctions = static_cast<int>(number(c_n_junctions));
    r.model = f[c_model];
    if (r.model != "independent" && r.model != "interacting")
      throw io::InputError(t.display, t.lines[i], "model", "'" + r.model + "' is neither independent nor interacting",
                           static_cast<int>(c_model) + 1);
    r.alpha_b = number(c_alpha);
    r.shape_exponent = number(c_n);
    r.endpoint_residual = number(c_end);
    r.residual_rms_m2 = number(c_res);
    r.noise_rms_p95_m2 = number(c_noise);
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
