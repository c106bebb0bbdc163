// PLY reader (ascii, binary little- and big-endian): vertex x/y/z of any
// numeric type, `element face` polygons and `element tristrips` (strips split
// by -1, as scanners write them). Used instead of OpenMesh's PLY reader, which
// knows no strips and, fed damaged binary files, crashed or hung in our fuzzing;
// here every count is checked against the bytes that follow before use.
#pragma once

#include <string>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

Status read_ply(const std::string& bytes, PolygonMesh* mesh);

}  // namespace srcodec
