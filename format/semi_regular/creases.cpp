#include "format/semi_regular/creases.h"

#include <algorithm>
#include <unordered_set>

namespace srcodec {
namespace {

uint64_t key(int32_t a, int32_t b) {
  return (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint32_t>(std::max(a, b));
}

}  // namespace

std::vector<std::array<int32_t, 2>> crease_edges_up_to(const TriangleHierarchy& hierarchy,
                                                       const std::vector<std::array<int32_t, 2>>& base_creases,
                                                       int32_t level) {
  if (base_creases.empty()) return {};
  std::unordered_set<uint64_t> crease;
  for (const auto& [a, b] : base_creases) crease.insert(key(a, b));
  // Level by level: a parent edge is a level-(j - 1) edge, whose status is
  // known once the coarser levels are done (ids are not in level order in
  // adaptive hierarchies).
  const int32_t top = std::min(level, hierarchy.max_level());
  std::vector<std::vector<int32_t>> by_level(static_cast<size_t>(std::max(top, 0)) + 1);
  for (int32_t v = hierarchy.base_vertex_count(); v < hierarchy.vertex_count(); ++v) {
    const int32_t l = hierarchy.vertex_level(v);
    if (l >= 1 && l <= top) by_level[l].push_back(v);
  }
  for (int32_t l = 1; l <= top; ++l)
    for (int32_t v : by_level[l]) {
      const auto [a, b] = hierarchy.parent_edge(v);
      if (!crease.erase(key(a, b))) continue;
      crease.insert(key(a, v));
      crease.insert(key(v, b));
    }
  std::vector<std::array<int32_t, 2>> out;
  out.reserve(crease.size());
  for (uint64_t k : crease) out.push_back({static_cast<int32_t>(k >> 32), static_cast<int32_t>(k & 0xffffffffu)});
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<uint8_t> crease_degrees(const TriangleHierarchy& hierarchy,
                                    const std::vector<std::array<int32_t, 2>>& creases) {
  std::vector<uint8_t> degree(static_cast<size_t>(hierarchy.vertex_count()), 0);
  for (const auto& edge : creases)
    for (int32_t v : edge)
      if (v >= 0 && v < hierarchy.vertex_count() && degree[v] < 255) ++degree[v];
  return degree;
}

}  // namespace srcodec
