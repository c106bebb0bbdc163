#include "remesh/adjacency.h"

#include <algorithm>

namespace srcodec {

Adjacency vertex_neighbors(size_t n, const std::vector<std::array<int32_t, 3>>& triangles) {
  Adjacency adj;
  adj.offsets.assign(n + 1, 0);
  for (const auto& t : triangles)
    for (int32_t v : t) adj.offsets[v + 1] += 2;
  for (size_t v = 0; v < n; ++v) adj.offsets[v + 1] += adj.offsets[v];
  std::vector<int32_t> fill(adj.offsets.begin(), adj.offsets.end() - 1);
  adj.items.resize(adj.offsets[n]);
  for (const auto& t : triangles) {
    for (int c = 0; c < 3; ++c) {
      adj.items[fill[t[c]]++] = t[(c + 1) % 3];
      adj.items[fill[t[c]]++] = t[(c + 2) % 3];
    }
  }
  // Sort and deduplicate each row in place, compacting as we go.
  int32_t out = 0;
  for (size_t v = 0; v < n; ++v) {
    auto first = adj.items.begin() + adj.offsets[v], last = adj.items.begin() + adj.offsets[v + 1];
    std::sort(first, last);
    last = std::unique(first, last);
    adj.offsets[v] = out;
    for (auto it = first; it != last; ++it)
      if (*it != static_cast<int32_t>(v)) adj.items[out++] = *it;  // a repeated corner is no edge
  }
  adj.offsets[n] = out;
  adj.items.resize(out);
  return adj;
}

Adjacency vertex_triangles(size_t n, const std::vector<std::array<int32_t, 3>>& triangles) {
  Adjacency adj;
  adj.offsets.assign(n + 1, 0);
  for (const auto& t : triangles)
    for (int32_t v : t) ++adj.offsets[v + 1];
  for (size_t v = 0; v < n; ++v) adj.offsets[v + 1] += adj.offsets[v];
  std::vector<int32_t> fill(adj.offsets.begin(), adj.offsets.end() - 1);
  adj.items.resize(adj.offsets[n]);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int32_t v : triangles[t]) adj.items[fill[v]++] = static_cast<int32_t>(t);
  return adj;
}

}  // namespace srcodec
