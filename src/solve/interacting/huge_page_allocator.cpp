#include "solve/interacting/huge_page_allocator.hpp"

#include <sys/mman.h>

#include <cstdlib>

namespace asperity {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;  // 2 MiB, x86-64's and arm64's usual size
constexpr std::size_t kHugeFrom = std::size_t{4} << 20;  // smaller blocks gain nothing
}  // namespace

void* huge_page_allocate(std::size_t bytes) {
  if (bytes < kHugeFrom) return ::operator new(bytes);
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: without huge pages, ordinary ones
#endif
  return p;
}

void huge_page_free(void* p, std::size_t bytes) noexcept {
  if (bytes < kHugeFrom) return ::operator delete(p);
  std::free(p);
}

}  // namespace asperity
