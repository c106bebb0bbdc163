// Which of the input's creases (remesh/features.h) the base mesh follows
// (RemeshOptions::creases): the crease edges, and the vertices it must keep
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
};

// With CreaseMode::kAuto the remesher follows a mesh's creases only if the
// curves long enough to follow would take at least this share of its base's
// edges (about 3 per base vertex), else none: on a part made of creases (a
// CAD part) they are the shape; on a scan or a sculpt they are a few ridges
// whose constraints cost the base more than their sharpness saves the
// coding. Over the whole corpus the CAD part's share is more than four times
// the largest of the scans' and sculpts', and this is the geometric mean of
// the two (the figures are in docs/remesh_design.md, "Creases").
inline constexpr double kAutoCreaseEdgeShare = 0.075;

// The length of the crease curves long enough to follow, in base edges; 0
// without base_vertices.
double followable_base_edges(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options);

// The creases of `features` (detected on `mesh`) as build_base_mesh takes
// them: the crease edges of the curves kept, and fixed the features'
// corners and ends on them and every vertex not on exactly two kept crease
// edges away from the boundary (where creases branch, stop, or run into
// the boundary).
BaseMeshCreases base_creases(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options);

}  // namespace srcodec
