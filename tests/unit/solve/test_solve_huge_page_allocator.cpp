// solve/interacting/huge_page_allocator.hpp: large blocks aligned to 2 MiB (so that whole huge
// pages can back them), small ones from operator new; contents and copies are those of any vector.
#include <catch2/catch.hpp>

#include <cstdint>
#include <numeric>
#include <vector>

#include "solve/interacting/huge_page_allocator.hpp"

namespace asperity {

TEST_CASE("the huge-page allocator aligns large blocks to 2 MiB and keeps what is stored", "[solve]") {
  using Big = std::vector<double, HugePageAllocator<double>>;
  const std::size_t n = 3 * (std::size_t{1} << 20) + 7;  // 24 MiB and a few doubles: rounded up inside
  Big a(n);
  CHECK(reinterpret_cast<std::uintptr_t>(a.data()) % (std::uintptr_t{2} << 20) == 0);
  std::iota(a.begin(), a.end(), 0.0);
  const Big b = a;  // a second large block
  CHECK(reinterpret_cast<std::uintptr_t>(b.data()) % (std::uintptr_t{2} << 20) == 0);
  CHECK(b[0] == 0.0);
  CHECK(b[n - 1] == static_cast<double>(n - 1));
  CHECK(std::accumulate(b.begin(), b.end(), 0.0) == 0.5 * static_cast<double>(n) * static_cast<double>(n - 1));
  // Small blocks (under 4 MiB) take the ordinary path and still hold their values.
  std::vector<int, HugePageAllocator<int>> s(1000, 3);
  s.push_back(4);
  CHECK(std::accumulate(s.begin(), s.end(), 0) == 3004);
}

}  // namespace asperity
