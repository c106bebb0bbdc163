// PLY files whose faces are stored as triangle strips (`element tristrips`,
// strips separated by -1), as many scanners write them. OpenMesh's reader only
// knows `element face`, so this small reader covers that case; it also reads
// `element face` lists in the same file.
#pragma once

#include <string>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

Status read_ply_tristrips(const std::string& path, PolygonMesh* mesh);

}  // namespace srcodec
