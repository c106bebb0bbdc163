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
};

// The creases of `features` (detected on `mesh`) as build_base_mesh takes
// them: the crease edges of the curves kept, and fixed the features'
// corners and ends on them and every vertex not on exactly two kept crease
// edges away from the boundary (where creases branch, stop, or run into
// the boundary).
BaseMeshCreases base_creases(const TriangleMesh& mesh, const Features& features, const BaseCreaseOptions& options);

}  // namespace srcodec
