// A range of memory, as format/prefault.h takes it: apart so that classes
// that only hand their arrays' ranges out (format/semi_regular/hierarchy.h) do not pull
// in the prefault thread's headers.
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

}  // namespace srcodec
