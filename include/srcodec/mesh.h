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

}  // namespace srcodec
