// Compressed-row vertex adjacency of a triangle list, shared by the remesher's
// stages (Lloyd assignment, cell connectivity, fold checks).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace srcodec {

// Rows of items per vertex: row v is items[offsets[v] .. offsets[v + 1]).
struct Adjacency {
  std::vector<int32_t> offsets;
  std::vector<int32_t> items;
  size_t size() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  const int32_t* begin(int32_t v) const { return items.data() + offsets[v]; }
  const int32_t* end(int32_t v) const { return items.data() + offsets[v + 1]; }
};

// Neighbours of each of the `vertex_count` vertices through triangle edges:
// sorted, each once, never the vertex itself. Indices must be in range.
Adjacency vertex_neighbors(size_t vertex_count, const std::vector<std::array<int32_t, 3>>& triangles);

// Indices of the triangles around each vertex, in increasing order.
Adjacency vertex_triangles(size_t vertex_count, const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace srcodec
