// Normals for shading a mesh whose crease edges must look sharp: a vertex
// gets one normal per sector, the fan of its triangles between two crease
// edges, so that light is not averaged across a crease (a vertex on none has
// one sector and the usual smooth normal). What `srcodec decode` writes to
// OBJ and the browser's loader draws for files with creases.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

struct SectorNormals {
  // One per sector, numbered vertex by vertex (vertex v's sectors are
  // contiguous), at least one per vertex: without creases sector v is
  // vertex v. The area-weighted average of the sector's triangle normals,
  // unit length; zero when its triangles have no area.
  std::vector<Eigen::Vector3f> normals;
  std::vector<int32_t> vertex;                  // per sector: its vertex
  std::vector<std::array<int32_t, 3>> corners;  // per triangle: the sector of each corner
};

// `creases`: pairs of vertex ids of `mesh`, in either order; a pair that is
// not an edge of `mesh` splits nothing. Two triangles at a vertex are in one
// sector when a chain of them sharing non-crease edges at that vertex joins
// them, so a crease that ends at a vertex (a dart) leaves it one sector.
// Triangle and crease ids must be vertices of `mesh`.
SectorNormals crease_normals(const TriangleMesh& mesh, const std::vector<std::array<int32_t, 2>>& creases);

// The public API's crease edges (two vertex ids per edge, as
// Decoded::crease_edges) as pairs, checked: an even count, every id below
// `vertex_count`.
StatusOr<std::vector<std::array<int32_t, 2>>> crease_pairs(const std::vector<uint32_t>& ids, size_t vertex_count);

}  // namespace srcodec
