// Mesh files in and out. Reading uses our own parsers, one per format
// (format/mesh_files/obj_reader.h, off_reader.h, ply_reader.h, stl_reader.h): OpenMesh's
// crashed, hung or aborted on damaged files in our fuzzing (fuzz/). They fill
// a raw PolygonMesh, checked for what would make later stages misbehave:
// missing or empty files, unknown formats, indices out of range, non-finite
// coordinates, no faces.
#pragma once

#include <string>

#include "format/crease_normals.h"
#include "format/mesh.h"
#include "format/mesh_files/mesh_clean.h"
#include "format/status.h"

namespace srcodec {

// The file as written: polygons, duplicates and unreferenced vertices kept.
StatusOr<PolygonMesh> read_polygon_mesh(const std::string& path);

// read_polygon_mesh followed by clean_mesh; `report` (optional) says what the
// cleaning changed.
StatusOr<TriangleMesh> read_triangle_mesh(const std::string& path, CleanReport* report = nullptr);

// Writes OBJ, PLY (binary little-endian), OFF or STL by the path's
// extension. The file is written beside the target and renamed into place,
// so a failure never leaves a partial file or damages one that was there.
// With `normals` (crease_normals' of `mesh`), an OBJ gets a `vn` line per
// normal and faces `f v//vn`; the other formats have no normals per corner
// and are written without them.
Status write_mesh(const TriangleMesh& mesh, const std::string& path, const SectorNormals* normals = nullptr);

// Whether write_mesh writes the normals it is given to a file at `path`
// (by its extension: OBJ only).
bool keeps_corner_normals(const std::string& path);

// Lower-case extension with its dot (".obj"), or "" if none.
std::string file_extension(const std::string& path);

}  // namespace srcodec
