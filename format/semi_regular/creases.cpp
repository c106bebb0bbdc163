#include "format/semi_regular/creases.h"

#include <algorithm>

namespace srcodec {

std::vector<std::array<int32_t, 2>> refined_crease_edges(const std::vector<std::array<int32_t, 2>>& creases,
                                                         const TriangleHierarchy& hierarchy, const int32_t* begin,
                                                         const int32_t* end) {
  std::vector<int32_t> split(creases.size(), -1);
  for (const int32_t* v = begin; v != end; ++v) {
    const auto [a, b] = hierarchy.parent_edge(*v);
    const std::array<int32_t, 2> key{std::min(a, b), std::max(a, b)};
    const auto it = std::lower_bound(creases.begin(), creases.end(), key);
    if (it != creases.end() && *it == key) split[static_cast<size_t>(it - creases.begin())] = *v;
  }
  std::vector<std::array<int32_t, 2>> out;
  out.reserve(2 * creases.size());
  for (size_t i = 0; i < creases.size(); ++i) {
    const auto [a, b] = creases[i];
    const int32_t v = split[i];
    if (v < 0) {
      out.push_back(creases[i]);
      continue;
    }
    out.push_back({std::min(a, v), std::max(a, v)});
    out.push_back({std::min(v, b), std::max(v, b)});
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::array<int32_t, 2>> crease_edges_up_to(const TriangleHierarchy& hierarchy,
                                                       const std::vector<std::array<int32_t, 2>>& base_creases,
                                                       int32_t level) {
  std::vector<std::array<int32_t, 2>> creases = base_creases;
  const int32_t top = std::min(level, hierarchy.max_level());
  if (creases.empty() || top < 1) return creases;
  // Level by level: a parent edge is a level-(j - 1) edge (ids are not in
  // level order in adaptive hierarchies).
  std::vector<std::vector<int32_t>> by_level(static_cast<size_t>(top) + 1);
  for (int32_t v = hierarchy.base_vertex_count(); v < hierarchy.vertex_count(); ++v) {
    const int32_t l = hierarchy.vertex_level(v);
    if (l >= 1 && l <= top) by_level[l].push_back(v);
  }
  for (int32_t l = 1; l <= top && !creases.empty(); ++l)
    creases = refined_crease_edges(creases, hierarchy, by_level[l].data(), by_level[l].data() + by_level[l].size());
  return creases;
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
