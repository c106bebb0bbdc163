// Mesh files in and out. Reading uses our own parsers, one per format
// (format/mesh_files/obj_reader.h, off_reader.h, ply_reader.h, stl_reader.h): OpenMesh's
// crashed, hung or aborted on damaged files in our fuzzing (fuzz/). They fill
// a raw PolygonMesh, checked for what would make later stages misbehave:
// missing or empty files, unknown formats, indices out of range, non-finite
// coordinates, no faces.
#pragma once

#include <string>

#include "format/mesh.h"
#include "format/mesh_files/mesh_clean.h"
#include "format/status.h"

namespace srcodec {

// The file as written: polygons, duplicates and unreferenced vertices kept.
StatusOr<PolygonMesh> read_polygon_mesh(const std::string& path);

// read_polygon_mesh followed by clean_mesh; `report` (optional) says what the
// cleaning changed.
StatusOr<TriangleMesh> read_triangle_mesh(const std::string& path, CleanReport* report = nullptr);

// Writes OBJ or PLY (binary little-endian) by the path's extension. The file
// is written beside the target and renamed into place, so a failure never
// leaves a partial file or damages one that was there.
Status write_mesh(const TriangleMesh& mesh, const std::string& path);

// Lower-case extension with its dot (".obj"), or "" if none.
std::string file_extension(const std::string& path);

}  // namespace srcodec
