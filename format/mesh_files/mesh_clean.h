// Basic input cleaning shared by every command: weld exactly coincident
// positions, triangulate polygons without creating duplicate or non-manifold
// faces, drop degenerate and duplicate faces (a zero-area triangle whose
// corners are distinct and collinear is first folded into its neighbour
// across its longest edge, which is split at the middle corner, so that
// dropping it opens no hole), drop unreferenced vertices.
#pragma once

#include <cstddef>

#include "format/mesh.h"

namespace srcodec {

struct CleanReport {
  size_t welded_vertices = 0;        // vertices merged into an earlier one at the same position
  size_t polygons_triangulated = 0;  // faces with more than 3 corners
  size_t degenerate_faces = 0;       // repeated corner after welding, or zero area
  size_t split_faces = 0;            // split at a zero-area neighbour's middle corner (see above)
  size_t duplicate_faces = 0;        // same vertex set as an earlier face
  size_t unreferenced_vertices = 0;  // vertices no kept face uses
};

// Positions keep their order (minus the dropped ones); faces keep their order
// and orientation (a split face's two halves in its place).
TriangleMesh clean_mesh(const PolygonMesh& input, CleanReport* report = nullptr);

}  // namespace srcodec
