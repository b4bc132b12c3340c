#include "surface/segmentation.hpp"

#include <algorithm>
#include <stdexcept>

namespace asperity {

std::vector<ContactCluster> contact_clusters(const std::vector<unsigned char>& in_contact, std::size_t n,
                                             double pixel_m, Connectivity connectivity) {
  if (in_contact.size() != n * n) throw std::invalid_argument("contact_clusters: the mask is not n x n");
  std::vector<unsigned char> seen(n * n, 0);
  std::vector<std::size_t> stack;
  std::vector<ContactCluster> out;
  const double c = 0.5 * static_cast<double>(n - 1);
  const int reach = connectivity == Connectivity::eight ? 1 : 0;
  for (std::size_t start = 0; start < n * n; ++start) {
    if (!in_contact[start] || seen[start]) continue;
    ContactCluster k;
    double sx = 0, sy = 0;
    stack.assign(1, start);
    seen[start] = 1;
    while (!stack.empty()) {  // flood fill (iterative: no recursion depth limit)
      const std::size_t p = stack.back();
      stack.pop_back();
      const std::size_t i = p / n, j = p % n;
      ++k.pixels;
      sx += static_cast<double>(j), sy += static_cast<double>(i);
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          if ((di == 0 && dj == 0) || (reach == 0 && di != 0 && dj != 0)) continue;
          const long ii = static_cast<long>(i) + di, jj = static_cast<long>(j) + dj;
          if (ii < 0 || jj < 0 || ii >= static_cast<long>(n) || jj >= static_cast<long>(n)) continue;
          const std::size_t q = static_cast<std::size_t>(ii) * n + static_cast<std::size_t>(jj);
          if (in_contact[q] && !seen[q]) seen[q] = 1, stack.push_back(q);
        }
    }
    k.area_m2 = static_cast<double>(k.pixels) * pixel_m * pixel_m;
    k.x_m = (sx / static_cast<double>(k.pixels) - c) * pixel_m;
    k.y_m = (sy / static_cast<double>(k.pixels) - c) * pixel_m;
    out.push_back(k);
  }
  std::sort(out.begin(), out.end(), [](const ContactCluster& a, const ContactCluster& b) {
    if (a.pixels != b.pixels) return a.pixels > b.pixels;
    return a.x_m != b.x_m ? a.x_m < b.x_m : a.y_m < b.y_m;
  });
  return out;
}

}  // namespace asperity
