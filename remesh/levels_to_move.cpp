#include "remesh/levels_to_move.h"

#include "format/semi_regular/creases.h"
#include "remesh/geometry.h"

namespace srcodec {

LevelsToMove levels_to_move(const TriangleHierarchy& hierarchy, int32_t levels, size_t base_vertices,
                            size_t vertices, const std::vector<std::array<int32_t, 2>>& base_creases) {
  LevelsToMove out;
  for (int32_t l = 0; l <= levels; ++l) out.triangles.push_back(hierarchy.level_triangles(l));
  out.fixed = boundary_vertices(vertices, out.triangles.back());
  for (const auto& edge : crease_edges_up_to(hierarchy, base_creases, levels))
    for (int32_t v : edge)
      if (static_cast<size_t>(v) < vertices) out.fixed[v] = 1;
  for (size_t b = 0; b < base_vertices && b < vertices; ++b)
    out.fixed[b] = out.fixed[b] ? LevelsToMove::kFixed : LevelsToMove::kOnInputVertices;
  return out;
}

}  // namespace srcodec
