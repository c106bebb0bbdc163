// Prefaulting memory that is about to be written.
//
// The first write to each 4 KB page of fresh memory is a page fault. A decode
// writes tens of megabytes of fresh arrays, and on the bunny's whole stream
// the faults were a quarter of its CPU time. One madvise(MADV_POPULATE_WRITE)
// call (Linux 5.14 and later) maps a whole range writable at once, leaving its
// contents as they are; elsewhere, or on older kernels, it does nothing and
// the pages fault in as they are written.
#pragma once

#include <cstddef>
#include <vector>

namespace srcodec {

struct MemoryRange {
  const void* data = nullptr;
  size_t bytes = 0;
};

// The memory of `v` up to its capacity.
template <typename T, typename A>
MemoryRange capacity_of(const std::vector<T, A>& v) {
  return {v.data(), v.capacity() * sizeof(T)};
}

// Maps the whole pages inside the range writable, if the system can; false
// when it cannot (another system, an older kernel, nothing mapped there).
// Safe while other threads write there, and on memory freed meanwhile: it
// changes no byte.
bool prefault(const MemoryRange& range);

}  // namespace srcodec
