// Which of the input's creases (remesh/features.h) the base mesh follows
// (RemeshOptions::features): the crease edges, and the vertices it must keep
// where creases meet, turn or end.
#pragma once

#include <cstddef>

#include "format/mesh.h"
#include "remesh/base_mesh.h"
#include "remesh/features.h"

namespace srcodec {

struct BaseCreaseOptions {
  // A crease curve (corner or end to corner or end) shorter than this many
  // base edges is left to the wavelet: the base mesh could follow it only
  // with base vertices closer together than its own spacing, whose thin
  // triangles the refinement folds. One edge: the shortest a chain of base
  // edges can be.
  double min_base_edges = 1.0;
  // The base mesh's vertices, which set its edge length (0: keep every
  // crease).
  size_t base_vertices = 0;
  // The curves kept are followed only if they would take at least this
  // share of the base's edges (about 3 per base vertex), else none is: on
  // a part made of creases (a CAD part) they are the shape, on a scan or a
  // sculpt they are a few ridges whose constraints cost the base more than
  // their sharpness saves the coding (docs/remesh_design.md, "Creases").
  // 0: follow any.
  double min_edge_share = 0.0;
};

// BaseCreaseOptions::min_edge_share when the remesher decides by itself
// (CreaseMode::kAuto): over the whole corpus, the shares fall into two
// groups a decade apart, and this is the middle of the gap on a log scale
// (the figures are in docs/remesh_design.md, "Creases").
inline constexpr double kAutoCreaseEdgeShare = 0.05;

// The share of the base's edges (about 3 per base vertex) the crease
// curves long enough to follow would take, in base edge lengths; 0 without
// base_vertices.
double crease_edge_share(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options);

// The creases of `features` (detected on `mesh`) as build_base_mesh takes
// them: the crease edges of the curves kept, and fixed the features'
// corners and ends on them and every vertex not on exactly two kept crease
// edges away from the boundary (where creases branch, stop, or run into
// the boundary); nothing when the curves kept fall short of
// min_edge_share.
BaseMeshCreases base_creases(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options);

}  // namespace srcodec
