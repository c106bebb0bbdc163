// Basic input cleaning shared by every command: weld exactly coincident
// positions, triangulate polygons without creating duplicate or non-manifold
// faces, drop degenerate and duplicate faces, drop unreferenced vertices.
#pragma once

#include <cstddef>

#include "format/mesh.h"

namespace srcodec {

struct CleanReport {
  size_t welded_vertices = 0;        // vertices merged into an earlier one at the same position
  size_t polygons_triangulated = 0;  // faces with more than 3 corners
  size_t degenerate_faces = 0;       // repeated corner after welding, or zero area
  size_t duplicate_faces = 0;        // same vertex set as an earlier face
  size_t unreferenced_vertices = 0;  // vertices no kept face uses
};

// Positions keep their order (minus the dropped ones); faces keep their order
// and orientation.
TriangleMesh clean_mesh(const PolygonMesh& input, CleanReport* report = nullptr);

}  // namespace srcodec
