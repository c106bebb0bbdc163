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

// Per vertex, the index of its edge-connected component: components are
// numbered in the order of their lowest vertex; a vertex in no triangle is
// a component of its own.
std::vector<int32_t> vertex_components(size_t vertex_count, const std::vector<std::array<int32_t, 3>>& triangles);

// Indices of the triangles around each vertex, in increasing order.
Adjacency vertex_triangles(size_t vertex_count, const std::vector<std::array<int32_t, 3>>& triangles);

// Per triangle, its neighbour across each edge (corner c to corner c + 1):
// -1 on the boundary, or where more than two triangles meet.
std::vector<std::array<int32_t, 3>> triangles_across(const std::vector<std::array<int32_t, 3>>& triangles);
// The triangles of `triangles` around vertex a (`around`: vertex_triangles)
// that also use vertex b: 1 on a boundary edge, 2 inside, 0 if ab is no edge.
int triangles_on_edge(const Adjacency& around, const std::vector<std::array<int32_t, 3>>& triangles, int32_t a,
                      int32_t b);

// Calls edge(a, b) for every boundary edge of `triangles` (one triangle on
// it), a to b the way that triangle runs.
template <class Edge>
void for_each_boundary_edge(const std::vector<std::array<int32_t, 3>>& triangles, const Adjacency& around, Edge&& edge) {
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) {
      const int32_t a = t[c], b = t[(c + 1) % 3];
      if (triangles_on_edge(around, triangles, a, b) == 1) edge(a, b);
    }
}

// The boundary loops of `triangles` (over `vertex_count` vertices;
// `around`: vertex_triangles), each walked the way its triangles run along
// it, from its lowest vertex. A loop through a vertex with two boundary
// edges leaving it is not a simple cycle and is left out.
std::vector<std::vector<int32_t>> boundary_loops(size_t vertex_count,
                                                 const std::vector<std::array<int32_t, 3>>& triangles,
                                                 const Adjacency& around);

}  // namespace srcodec
