// The remesher's input preparation (DESIGN.md, remesh/ step 1), run after
// format/'s clean_mesh: split a triangle mesh into connected pieces that are
// each edge-manifold, vertex-manifold and consistently oriented, so every
// later stage (and OpenMesh) can treat a piece as one surface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

struct ComponentMesh {
  TriangleMesh mesh;                     // one edge-manifold, vertex-manifold, consistently oriented component
  std::vector<int32_t> source_vertex;    // per vertex of `mesh`: its index in the input (copies share a source)
  std::vector<int32_t> source_triangle;  // per triangle of `mesh`: its index in the input
};

struct ManifoldReport {
  size_t nonmanifold_edges_cut = 0;       // input edges with > 2 faces, whose extra faces were detached
  size_t nonmanifold_vertices_split = 0;  // input vertices that became more than one output vertex
  size_t faces_flipped = 0;               // output faces whose orientation differs from the input's
  size_t nonorientable_components = 0;    // pieces with no consistent orientation (e.g. a Moebius band)
};

// Splits `mesh` into components and repairs each one:
//  - an edge with more than two faces is cut open; faces that still meet
//    around both of its ends stay joined, and the remaining ones are joined
//    again two at a time (consistently oriented pairs first) wherever that
//    keeps every vertex manifold;
//  - every vertex gets one copy per edge-connected fan of faces, so
//    components never share a vertex and "vertex-connected" equals
//    "edge-connected";
//  - faces are flipped (breadth-first from the lowest face index) to agree
//    with their neighbours. A closed component then faces outward (positive
//    signed volume); an open one keeps the orientation most of its input
//    faces had.
// A non-orientable piece is not an error: it is cut open along the edges
// where the orientations clash (vertices there are duplicated), which leaves
// it orientable, and counted in `nonorientable_components`.
//
// Components are ordered by their smallest input triangle index; triangles
// keep their input order inside a component, and vertices are numbered in
// order of first use. The union of all triangles is the input's.
//
// Errors (kInvalidMesh): a vertex index out of range, or a triangle that
// repeats a vertex (clean_mesh removes those). Duplicate and zero-area
// triangles are accepted.
StatusOr<std::vector<ComponentMesh>> split_into_manifold_components(const TriangleMesh& mesh,
                                                                    ManifoldReport* report = nullptr);

}  // namespace srcodec
