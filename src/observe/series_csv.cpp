#include "observe/series_csv.hpp"

#include <algorithm>
#include <stdexcept>

#include "io/numbers.hpp"
#include "scene/scene.hpp"

namespace asperity {

void write_series_csv(std::ostream& out, const std::vector<Sample>& samples, const std::vector<std::string>& series) {
  const auto& all = all_series();
  for (const auto& name : series)
    if (std::find(all.begin(), all.end(), name) == all.end())
      throw std::invalid_argument("unknown series column '" + name + "'");
  std::vector<std::size_t> cols;  // indices into all_series(), canonical order, no duplicates
  for (std::size_t c = 0; c < all.size(); ++c)
    if (std::find(series.begin(), series.end(), all[c]) != series.end()) cols.push_back(c);

  for (std::size_t j = 0; j < cols.size(); ++j) out << (j ? "," : "") << all[cols[j]];
  out << '\n';
  std::string line;
  for (const auto& s : samples) {
    line.clear();
    for (std::size_t j = 0; j < cols.size(); ++j) {
      if (j) line += ',';
      switch (cols[j]) {
        case 0:
          line += io::format_g17(s.t);
          break;
        case 1:
          line += io::format_g17(s.X);
          break;
        case 2:
          line += io::format_g17(s.V);
          break;
        case 3:
          line += io::format_g17(s.Q);
          break;
        case 4:
          line += io::format_g17(s.A);
          break;
        case 5:
          line += std::to_string(s.n_slipping);
          break;
        case 6:
          line += std::to_string(s.n_intact);
          break;
        default:
          break;
      }
    }
    line += '\n';
    out << line;
  }
}

}  // namespace asperity
