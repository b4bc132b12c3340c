#pragma once
// An allocator for large matrices read in long streams (the compliance G of the interacting
// solver: N² doubles read row by row at every pass). Blocks of 4 MiB or more are aligned to 2 MiB
// and marked for transparent huge pages (madvise; Debian's default mode): a 200 MB matrix then
// takes 100 TLB entries instead of 50,000, and the hardware prefetcher, which stops at every page
// boundary, runs on through 2 MiB. Where the kernel has no huge pages the advice is ignored;
// smaller blocks come from operator new.
#include <cstddef>
#include <new>

namespace asperity {

void* huge_page_allocate(std::size_t bytes);  // nullptr never: throws std::bad_alloc
void huge_page_free(void* p, std::size_t bytes) noexcept;

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(huge_page_allocate(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { huge_page_free(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace asperity
