// The base mesh of the remesher (Kammoun, Payan, Antonini §III-A, last
// paragraph; DESIGN.md remesh/ step 5): every vertex that is not a Voronoi
// site is removed by a half-edge collapse, as in MAPS (Lee, Sweldens,
// Schröder, Cowsar, Dobkin 1998), and the parameterization of the input over
// the base mesh is built along the way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "format/semi_regular/param.h"

namespace srcodec {

struct BaseMesh {
  // The base triangles. positions[b] is the position of input vertex
  // input_vertex[b]; triangles keep the input's orientation.
  TriangleMesh mesh;
  std::vector<int32_t> input_vertex;  // per base vertex: the input vertex it is
  // Per input vertex: where it lies on the base domain. A vertex that became
  // base vertex b has weight 1 at b's corner of one of b's triangles.
  std::vector<ParamPoint> param;
};

struct BaseMeshReport {
  size_t collapses = 0;         // half-edge collapses done
  size_t promoted_vertices = 0;  // non-site vertices no legal collapse could remove, kept as base vertices
  size_t refused_link = 0;       // collapse attempts refused by the link condition / boundary rules
  size_t refused_fold = 0;       // attempts refused because a face would flip in 3D
  size_t refused_param = 0;      // attempts refused because the flattened 1-ring fan would be invalid
  // Of `collapses`, those into a same-cell neighbour nearer the site; the
  // rest are the fallback into any legal neighbour.
  size_t collapses_towards_site = 0;
  // Of `promoted_vertices`, the non-site boundary vertices kept on purpose:
  // one per run of a cell's boundary vertices (or three on a boundary loop
  // inside one cell), so the base boundary follows the cells.
  size_t boundary_vertices_kept = 0;
  // Points found more than 1e-6 (in barycentrics) outside every triangle of
  // the new fan, placed on the nearest one.
  size_t clamped_points = 0;
  double seconds = 0.0;
};

// Builds the base mesh whose vertices are `sites` (input vertex indices, all
// distinct) and the parameterization of every input vertex over it.
//  - `mesh` is one edge-connected, manifold, consistently oriented component
//    with every vertex used (an element of split_into_manifold_components's
//    result); boundaries and any genus are allowed, and the base mesh has the
//    same boundary loops, genus and orientation.
//  - `cell_of` (per input vertex, index into `sites`; may be empty) steers the
//    collapses: a vertex is first collapsed towards a neighbour of its own
//    cell that is nearer (in edges) to the cell's site, so the base mesh's
//    triangles join neighbouring cells.
//  - A collapse is done only when it keeps the mesh a manifold of the same
//    topology (link condition; boundary vertices only along boundary edges),
//    flips no face (the normal of every changed face keeps a positive dot
//    product with its normal before), and the fan around the kept vertex is
//    valid in the 1-ring's conformal flattening (MAPS's z^a map), which is
//    where the removed points find their new triangle and barycentrics.
//  - A non-site vertex that can never be collapsed is kept as a base vertex
//    and counted in report->promoted_vertices: the result is always a valid
//    mesh, never a partial one.
//  - Deterministic.
// Errors: kInvalidArgument for bad or repeated site indices or a cell_of of
// the wrong size; kInvalidMesh when `mesh` is not as described above.
StatusOr<BaseMesh> build_base_mesh(const TriangleMesh& mesh, const std::vector<int32_t>& sites,
                                   const std::vector<int32_t>& cell_of, BaseMeshReport* report = nullptr);

}  // namespace srcodec
