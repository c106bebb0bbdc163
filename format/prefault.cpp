#include "format/prefault.h"

#include <algorithm>
#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace srcodec {

bool prefault(const MemoryRange& range) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  static const uintptr_t page = static_cast<uintptr_t>(sysconf(_SC_PAGESIZE));
  if (page == 0 || (page & (page - 1)) != 0) return false;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(range.data) + page - 1) & ~(page - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(range.data) + range.bytes) & ~(page - 1);
  // Advice: on a kernel without it (EINVAL) the pages fault in as written.
  return end <= begin || madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE) == 0;
#else
  (void)range;
  return false;
#endif
}

BackgroundPrefault::BackgroundPrefault(std::vector<MemoryRange> ranges, size_t min_bytes) {
  size_t bytes = 0;
  for (const MemoryRange& range : ranges) bytes += range.bytes;
  if (bytes < min_bytes || bytes == 0) return;
  thread_ = std::thread([this, ranges = std::move(ranges)] {
    // Steps end at multiples of kStep in the address space, so on page
    // boundaries: prefault() maps only the whole pages inside a step.
    constexpr uintptr_t kStep = uintptr_t{4} << 20;
    for (const MemoryRange& range : ranges) {
      const uintptr_t end = reinterpret_cast<uintptr_t>(range.data) + range.bytes;
      for (uintptr_t at = reinterpret_cast<uintptr_t>(range.data); at < end;) {
        if (stop_.load(std::memory_order_relaxed)) return;
        const uintptr_t next = std::min(end, (at / kStep + 1) * kStep);
        prefault({reinterpret_cast<const void*>(at), next - at});
        at = next;
      }
    }
  });
}

BackgroundPrefault::~BackgroundPrefault() {
  stop_.store(true, std::memory_order_relaxed);
  if (thread_.joinable()) thread_.join();
}

}  // namespace srcodec
