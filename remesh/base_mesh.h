// The base mesh of the remesher (Kammoun, Payan, Antonini §III-A, last
// paragraph; DESIGN.md remesh/ step 5): every vertex that is not a Voronoi
// site is removed by a half-edge collapse, as in MAPS (Lee, Sweldens,
// Schröder, Cowsar, Dobkin 1998), and the parameterization of the input over
// the base mesh is built along the way.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "format/semi_regular/param.h"

namespace srcodec {

// Sharp features the base mesh keeps, as MAPS keeps feature lines (Lee et
// al. 1998, §3.4): a vertex on a crease is removed only by a collapse along
// the crease into its neighbour on it, so every crease becomes a chain of
// base edges through the cells it crosses; the vertices where creases meet
// or end are never removed.
struct BaseMeshCreases {
  // Input edges (a < b) along which the surface is sharp. Each vertex on
  // them must have exactly two, or be in `fixed`.
  std::vector<std::array<int32_t, 2>> edges;
  // Input vertices kept as base vertices whatever their cells: corners and
  // ends of the creases (remesh/features.h).
  std::vector<int32_t> fixed;
};

struct BaseMesh {
  // The base triangles. positions[b] is the position of input vertex
  // input_vertex[b]; triangles keep the input's orientation.
  TriangleMesh mesh;
  std::vector<int32_t> input_vertex;  // per base vertex: the input vertex it is
  // Per input vertex: where it lies on the base domain. A vertex that became
  // base vertex b has weight 1 at b's corner of one of b's triangles.
  std::vector<ParamPoint> param;
  // The base edges that follow the input's creases (BaseMeshCreases), each
  // (a, b) with a < b in base vertex numbers, sorted; empty without creases.
  std::vector<std::array<int32_t, 2>> crease_edges;
  // The creases it was built to follow (build_base_mesh's `creases`), in
  // input vertex numbers: where the refinement keeps its crease vertices.
  BaseMeshCreases input_creases;
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
  // Of `promoted_vertices`, those on creases: the fixed ones, and one per
  // run of a cell's crease vertices (as on the boundary).
  size_t crease_vertices_kept = 0;
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
//  - With `creases`, crease vertices collapse only along their crease, in
//    the boundary's phase (one kept per run of a cell), and the fixed ones
//    stay; the 1-ring of a crease vertex is flattened with each side of the
//    crease opened to π, so the points on the crease land on the base edge
//    that replaces it.
//  - Deterministic.
// Errors: kInvalidArgument for bad or repeated site indices, a cell_of of
// the wrong size, or creases that are not edges of `mesh` or branch at a
// vertex that is not fixed; kInvalidMesh when `mesh` is not as described
// above.
StatusOr<BaseMesh> build_base_mesh(const TriangleMesh& mesh, const std::vector<int32_t>& sites,
                                   const std::vector<int32_t>& cell_of, BaseMeshReport* report = nullptr,
                                   const BaseMeshCreases& creases = {});

}  // namespace srcodec
