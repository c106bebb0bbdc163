#include "format/prefault.h"

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

}  // namespace srcodec
