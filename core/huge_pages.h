// Transparent huge pages for large buffers: fewer page faults when they are first written, fewer TLB misses when read at random.
#pragma once

#include <cstddef>
#include <vector>

namespace prism {

// Asks the kernel to back the whole 2 MiB pages inside [data, data + bytes) with huge pages
// (madvise MADV_HUGEPAGE; Debian's default THP mode grants them only where asked). A hint: it
// changes no value, and does nothing where the system has no transparent huge pages.
void advise_huge_pages(void* data, size_t bytes);

// Resizes v to n value-initialised elements, asking for huge pages before the memory is first
// touched when it is fresh and large: an 8K environment map's texels take 384 MiB, whose first
// writes one 4 KiB page at a time cost about a second of page faults.
template <typename T>
void resize_on_huge_pages(std::vector<T>& v, size_t n) {
  if (n > v.capacity()) {
    v.reserve(n);
    advise_huge_pages(v.data() + v.size(), (n - v.size()) * sizeof(T));
  }
  v.resize(n);
}

}  // namespace prism
