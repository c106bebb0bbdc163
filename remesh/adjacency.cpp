#include "remesh/adjacency.h"

#include <algorithm>
#include <utility>

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

std::vector<std::array<int32_t, 3>> triangles_across(const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<std::array<int32_t, 3>> across(triangles.size(), {-1, -1, -1});
  std::vector<std::array<int32_t, 4>> edges;  // lower vertex, higher vertex, triangle, corner
  edges.reserve(3 * triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const auto [a, b] = std::minmax(triangles[t][c], triangles[t][(c + 1) % 3]);
      edges.push_back({a, b, static_cast<int32_t>(t), c});
    }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    if (j - i == 2) {
      across[static_cast<size_t>(edges[i][2])][static_cast<size_t>(edges[i][3])] = edges[i + 1][2];
      across[static_cast<size_t>(edges[i + 1][2])][static_cast<size_t>(edges[i + 1][3])] = edges[i][2];
    }
    i = j;
  }
  return across;
}

std::vector<int32_t> vertex_components(size_t n, const std::vector<std::array<int32_t, 3>>& triangles) {
  const Adjacency neighbours = vertex_neighbors(n, triangles);
  std::vector<int32_t> component(n, -1), stack;
  int32_t next = 0;
  for (size_t s = 0; s < n; ++s) {
    if (component[s] >= 0) continue;
    component[s] = next;
    stack.assign(1, static_cast<int32_t>(s));
    while (!stack.empty()) {
      const int32_t v = stack.back();
      stack.pop_back();
      for (const int32_t* u = neighbours.begin(v); u != neighbours.end(v); ++u)
        if (component[static_cast<size_t>(*u)] < 0) {
          component[static_cast<size_t>(*u)] = next;
          stack.push_back(*u);
        }
    }
    ++next;
  }
  return component;
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

int triangles_on_edge(const Adjacency& around, const std::vector<std::array<int32_t, 3>>& triangles, int32_t a,
                      int32_t b) {
  int shared = 0;
  for (const int32_t* t = around.begin(a); t != around.end(a); ++t)
    shared += std::find(triangles[*t].begin(), triangles[*t].end(), b) != triangles[*t].end();
  return shared;
}

std::vector<std::vector<int32_t>> boundary_loops(size_t n, const std::vector<std::array<int32_t, 3>>& triangles,
                                                 const Adjacency& around) {
  std::vector<int32_t> next(n, -1);
  std::vector<char> irregular(n, 0), visited(n, 0);
  for_each_boundary_edge(triangles, around, [&](int32_t a, int32_t b) {
    if (next[a] >= 0) irregular[a] = 1;
    next[a] = b;
  });
  std::vector<std::vector<int32_t>> loops;
  for (size_t start = 0; start < n; ++start) {
    if (next[start] < 0 || visited[start]) continue;
    std::vector<int32_t> walk;
    bool simple = true;
    int32_t v = static_cast<int32_t>(start);
    do {  // every vertex is walked once
      simple = simple && !irregular[v];
      visited[v] = 1;
      walk.push_back(v);
      v = next[v];
    } while (v >= 0 && !visited[v]);
    if (simple && v == static_cast<int32_t>(start)) loops.push_back(std::move(walk));
  }
  return loops;
}

}  // namespace srcodec
