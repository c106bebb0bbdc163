// Topology and geometry figures of a mesh, as `srcodec info` prints them.
// Definitions follow the corpus MANIFEST: edges are polygon edges; a
// non-manifold vertex is one whose incident faces form more than one
// edge-connected fan; components are vertex-connected over referenced vertices.
#pragma once

#include <cstddef>
#include <optional>

#include "format/mesh.h"

namespace srcodec {

struct MeshStats {
  size_t vertices = 0;             // all stored vertices
  size_t referenced_vertices = 0;  // used by at least one face
  size_t faces = 0;
  size_t triangles = 0;            // faces with exactly three corners
  size_t max_face_size = 0;
  size_t edges = 0;                // undirected
  size_t components = 0;
  size_t boundary_edges = 0;
  size_t boundary_loops = 0;       // connected pieces of the boundary-edge graph
  size_t nonmanifold_edges = 0;    // more than two incident faces
  size_t nonmanifold_vertices = 0;
  size_t orientation_inconsistent_edges = 0;  // two faces traversing the edge the same way
  size_t degenerate_faces = 0;     // repeated corner or zero area
  long euler_characteristic = 0;   // V_referenced - E + F
  std::optional<long> genus;       // only for manifold, orientable-looking meshes
  double bbox_diagonal = 0.0;

  bool is_manifold() const { return nonmanifold_edges == 0 && nonmanifold_vertices == 0; }
  bool is_closed() const { return boundary_edges == 0; }
};

MeshStats compute_stats(const PolygonMesh& mesh);

}  // namespace srcodec
