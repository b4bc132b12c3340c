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
  std::vector<TopographyShapeRow> rows;
  std::ifstream in(file);
  if (!in) return rows;
  const std::string display = file.generic_string();
  std::string line;
  std::vector<std::string> header;
  int line_no = 0;
  auto column = [&](const std::string& name) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it == header.end()) throw InputError(display, line_no, name, "column missing");
    return static_cast<std::size_t>(it - header.begin());
  };
  std::size_t c_seed = 0, c_load = 0, c_n_junctions = 0, c_model = 0, c_alpha = 0, c_n = 0, c_end = 0, c_res = 0,
              c_noise = 0;
  // A results table: far below this; the cap keeps a wrong file from exhausting memory.
  constexpr std::size_t kMaxRows = 100000;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) {
      header = csv_split(line);
      c_seed = column("seed"), c_load = column("P_N"), c_n_junctions = column("N"), c_model = column("model");
      c_alpha = column("alpha_b"), c_n = column("n"), c_end = column("endpoint_residual");
      c_res = column("residual_rms_m2"), c_noise = column("noise_rms_p95_m2");
      continue;
    }
    if (rows.size() >= kMaxRows) throw InputError(display, line_no, "", "more than 100000 rows");
    const auto f = csv_split(line);
    if (f.size() != header.size())
      throw InputError(display, line_no, "", std::to_string(f.size()) + " fields where the header has " +
                                                 std::to_string(header.size()));
    auto number = [&](std::size_t c) {
      double x = 0;
      if (scene_io::parse_double(f[c], x) != scene_io::NumberParse::ok || !std::isfinite(x))
        throw InputError(display, line_no, header[c], "not a finite number: '" + f[c] + "'", static_cast<int>(c) + 1);
      return x;
    };
    TopographyShapeRow r;
    r.seed = static_cast<int>(number(c_seed));
    r.load_N = number(c_load);
    r.junctions = static_cast<int>(number(c_n_junctions));
    r.model = f[c_model];
    if (r.model != "independent" && r.model != "interacting")
      throw InputError(display, line_no, "model", "'" + r.model + "' is neither independent nor interacting",
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
