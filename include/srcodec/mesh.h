// srcodec's plain triangle mesh, and mesh files in and out (OBJ, PLY, OFF,
// STL). Part of srcodec::decoder.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <srcodec/status.h>

namespace srcodec {

// An indexed triangle mesh. Positions are doubles so that a mesh read from a
// file and encoded, or decoded and written, loses no bit on the way.
struct Mesh {
  std::vector<double> positions;    // x, y, z of vertex 0, then of vertex 1, ...
  std::vector<uint32_t> triangles;  // three vertex indices per triangle, counter-clockwise seen from outside

  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return triangles.size() / 3; }
};

// Reads OBJ, PLY (ascii or binary; faces or triangle strips), OFF or STL (ascii
// or binary), chosen by the file's extension, and cleans it as `srcodec`
// does: coincident positions welded, unreferenced vertices and zero-area or
// duplicate faces dropped, polygons triangulated. Errors name the file and
// the line or byte where it went wrong.
StatusOr<Mesh> read_mesh(const std::string& path);

// Writes OBJ, PLY (binary), OFF or STL (binary) by the path's extension. The
// file is written beside the target and renamed into place: a failure leaves
// whatever was there untouched. OBJ and OFF keep every bit of each position.
Status write_mesh(const std::string& path, const Mesh& mesh);

// Normals that keep a mesh's sharp edges sharp when it is shaded. A vertex
// has one normal per sector, the fan of its triangles between two crease
// edges: the area-weighted average of their normals, so that light is not
// averaged across a crease. A vertex on no crease edge, or where a crease
// ends (a dart), has one: the usual smooth vertex normal.
struct CornerNormals {
  // x, y, z of each normal, unit length (zero where its triangles have no
  // area). Numbered vertex by vertex, at least one per vertex: without
  // crease edges, normal v is vertex v's.
  std::vector<float> normals;
  std::vector<uint32_t> vertices;  // the vertex of each normal
  // Per triangle corner, as Mesh::triangles: the index of its normal. A
  // renderer that takes one normal per vertex draws a vertex per normal (at
  // the position of `vertices`) with `corners` as the triangles.
  std::vector<uint32_t> corners;
};

// The normals of `mesh` split at `crease_edges` (two vertex ids per edge, as
// Decoded::crease_edges; a pair that is not an edge of the mesh splits
// nothing). Errors: a mesh write_mesh would refuse, an odd count or an id
// out of range in `crease_edges`.
StatusOr<CornerNormals> corner_normals(const Mesh& mesh, const std::vector<uint32_t>& crease_edges);

// write_mesh for a mesh with sharp edges (Decoded::crease_edges): an OBJ
// gets corner_normals' normals (a `vn` line each, faces `f v//vn`), so that
// viewers shade the creases sharp. Without crease edges, and in PLY, OFF and
// STL, which have no normals per corner, the file is write_mesh's.
Status write_mesh(const std::string& path, const Mesh& mesh, const std::vector<uint32_t>& crease_edges);

}  // namespace srcodec
