// A yes/no verdict per item, judged on both cores: each item is judged on
// its own, so the flags are those of a serial scan, and the caller counts or
// acts on them in the serial order.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstddef>
#include <vector>

namespace srcodec {

// flags[i] = judge(i) ? 1 : 0 for i in 0 .. count - 1; judge must only read.
template <class Judge>
std::vector<char> parallel_flags(size_t count, const Judge& judge) {
  std::vector<char> flags(count);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) flags[i] = judge(i) ? 1 : 0;
  });
  return flags;
}

}  // namespace srcodec
