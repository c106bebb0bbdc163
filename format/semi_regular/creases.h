// The crease edges of every level of a semi-regular mesh, from those of its
// base mesh (SemiRegularMesh::crease_edges): the two halves of a crease edge
// split by a new vertex are crease edges of the finer level, and no other
// edge a split makes is (the edges inside a split triangle and the green
// closure's cut it). The remesher keeps the vertices on these edges on the
// input's creases; the wavelet predicts along them with curve rules.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "format/semi_regular/hierarchy.h"

namespace srcodec {

// The crease edges of the level-j mesh from those of level j - 1 (`creases`,
// a < b, sorted) and level j's vertices [begin, end): a crease split by a
// vertex v gives its halves (a, v) and (v, b), one left unsplit (adaptive
// refinement) stays. Edges between new vertices and green closure edges
// lie inside the split triangles, never on a crease.
std::vector<std::array<int32_t, 2>> refined_crease_edges(const std::vector<std::array<int32_t, 2>>& creases,
                                                         const TriangleHierarchy& hierarchy, const int32_t* begin,
                                                         const int32_t* end);

// The crease edges of the mesh of level `level` of `hierarchy`
// (level_triangles(level); a < b, sorted, unique): the base creases, each
// replaced by its halves wherever a vertex of level <= `level` splits it.
// An adaptive level keeps the coarser crease edges it does not split;
// levels beyond max_level give the finest mesh's. Base creases must be
// (a < b) pairs of base vertices, sorted (LiftingPlan::build checks them).
std::vector<std::array<int32_t, 2>> crease_edges_up_to(const TriangleHierarchy& hierarchy,
                                                       const std::vector<std::array<int32_t, 2>>& base_creases,
                                                       int32_t level);

// Per vertex of `hierarchy`: how many of `creases` (crease_edges_up_to's
// result) it is on, saturated at 255: 2 along a crease, else where creases
// meet or end.
std::vector<uint8_t> crease_degrees(const TriangleHierarchy& hierarchy,
                                    const std::vector<std::array<int32_t, 2>>& creases);

}  // namespace srcodec
