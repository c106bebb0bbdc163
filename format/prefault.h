// Prefaulting memory that is about to be written.
//
// The first write to each 4 KB page of fresh memory is a page fault. A decode
// writes tens of megabytes of fresh arrays, and the faults are a large share
// of its CPU time (docs/codec_design.md). One madvise(MADV_POPULATE_WRITE)
// call (Linux 5.14 and later) maps a whole range writable at once, leaving its
// contents as they are; elsewhere, or on older kernels, it does nothing and
// the pages fault in as they are written.
#pragma once

#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

#include "format/memory_range.h"

namespace srcodec {

// Maps the whole pages inside the range writable, if the system can; false
// when it cannot (another system, an older kernel, nothing mapped there).
// Safe while other threads write there, and on memory freed meanwhile: it
// changes no byte.
bool prefault(const MemoryRange& range);

// Prefaults ranges on a thread of its own, a few megabytes at a time, while
// the caller goes on and writes them; when they hold at least `min_bytes`
// (a thread costs tens of microseconds). Destroying it stops the thread
// between two steps and joins it.
class BackgroundPrefault {
 public:
  BackgroundPrefault(std::vector<MemoryRange> ranges, size_t min_bytes);
  ~BackgroundPrefault();
  BackgroundPrefault(const BackgroundPrefault&) = delete;
  BackgroundPrefault& operator=(const BackgroundPrefault&) = delete;

  bool running() const { return thread_.joinable(); }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace srcodec
