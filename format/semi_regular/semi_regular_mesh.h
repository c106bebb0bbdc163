// The remesher's result and the wavelet stage's input: a base mesh whose
// triangles are refined by 1-to-4 splits (adaptively, balanced, closed
// conformingly by green bisections), with one position per vertex.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/semi_regular/hierarchy.h"

namespace srcodec {

struct SemiRegularMesh {
  // Level 0. Base vertex b is vertex b of the hierarchy and of `positions`.
  TriangleMesh base;
  // The split quadtree of every base triangle, each vertex's level and parent
  // edge, and the watertight mesh of every level (hierarchy.level_triangles).
  TriangleHierarchy hierarchy;
  // Per hierarchy vertex: its position. Voronoi sites are vertices of the
  // (oversampled) input the remesher ran on, except where the input is sparse
  // (then a point of the input surface) or ran out (an edge midpoint), and a
  // few sites moved to untangle folds; RefineLevelReport counts each kind.
  // With RemeshOptions::fit_surface (the default) the vertices above the
  // base mesh, but for the boundary's, then leave them along their normals
  // (remesh/fit.h); base vertices stay on input vertices, where the sites
  // are or, where the untangling moved them, others (remesh/untangle.h).
  std::vector<Eigen::Vector3d> positions;
  int32_t levels = 0;  // the finest level built (hierarchy.max_level() may be lower if nothing was split)
  // The base edges along which the surface is sharp (creases; the remesher
  // lays them along the input's feature curves, remesh/features.h), each as
  // (a, b) with a < b, sorted, no repeats. The wavelet predicts and updates
  // along them with curve rules, and so along every edge that refines one.
  // Empty: a smooth surface, the plain Butterfly everywhere.
  std::vector<std::array<int32_t, 2>> crease_edges;

  // The mesh of `level` as a plain triangle mesh: the vertices it uses (in
  // increasing vertex id order) and its triangles re-indexed to them.
  TriangleMesh level_mesh(int32_t level) const;
};

// The plain mesh of `triangles` (ids into `positions`): the vertices they use,
// in increasing id order, and the triangles re-indexed to them.
TriangleMesh compact_mesh(const std::vector<Eigen::Vector3d>& positions,
                          const std::vector<std::array<int32_t, 3>>& triangles);

}  // namespace srcodec
