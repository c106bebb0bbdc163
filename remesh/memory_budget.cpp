#include "remesh/memory_budget.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace srcodec {

uint64_t subdivided_vertices(uint64_t vertices, uint64_t triangles, int steps) {
  // A closed triangle mesh has 3/2 edges per triangle; boundaries add a few.
  double v = static_cast<double>(vertices), f = static_cast<double>(triangles), e = 1.5 * f;
  for (int s = 0; s < steps; ++s) {
    v += e;
    e = 2.0 * e + 3.0 * f;
    f *= 4.0;
  }
  return static_cast<uint64_t>(v);
}

uint64_t remesh_memory_estimate(uint64_t oversampled_vertices) {
  return static_cast<uint64_t>(std::ceil(kRemeshBytesPerVertex * static_cast<double>(oversampled_vertices)));
}

uint64_t available_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream fields(line);
    std::string key;
    uint64_t kilobytes = 0;
    if (fields >> key >> kilobytes && key == "MemAvailable:") return kilobytes * 1024;
  }
#if defined(_SC_AVPHYS_PAGES) && defined(_SC_PAGESIZE)
  const long pages = sysconf(_SC_AVPHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) return static_cast<uint64_t>(pages) * static_cast<uint64_t>(page);
#endif
  return 0;
}

std::string memory_text(uint64_t bytes) {
  char text[32];
  const double b = static_cast<double>(bytes);
  if (b >= 1e9)
    std::snprintf(text, sizeof text, "%.1f GB", b / 1e9);
  else
    std::snprintf(text, sizeof text, "%.0f MB", std::ceil(b / 1e6));
  return text;
}

}  // namespace srcodec
