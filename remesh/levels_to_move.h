// The levels of a semi-regular mesh as the stages after the refinement move
// its vertices: each level's triangles, and which vertices must stay.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/semi_regular/hierarchy.h"

namespace srcodec {

// Each level's triangles (levels 0 to `levels` of `hierarchy`), and the
// vertices the fit, the untangling and the coarsening's refit leave where
// they are (`fixed` nonzero): the base vertices (ids below `base_vertices`:
// the paper's sites, input vertices), the boundary vertices of the finest
// level (on the input's boundary) and the vertices on its crease edges
// (format/semi_regular/creases.h, from `base_creases`: on the input's
// creases), among `vertices`. The base vertices off the boundary and the
// creases are kOnInputVertices: the untangling may move them onto other
// input vertices (remesh/untangle.h), the rest keep them where they are.
struct LevelsToMove {
  static constexpr char kFixed = 1, kOnInputVertices = 2;
  std::vector<std::vector<std::array<int32_t, 3>>> triangles;
  std::vector<char> fixed;
};
LevelsToMove levels_to_move(const TriangleHierarchy& hierarchy, int32_t levels, size_t base_vertices,
                            size_t vertices, const std::vector<std::array<int32_t, 2>>& base_creases = {});

}  // namespace srcodec
