// OFF reader (text OFF, COFF, NOFF, ...): the first three numbers of each
// vertex line, then per face line a corner count and that many indices.
// Used instead of OpenMesh's OFF reader, which in our fuzzing read a face
// claiming four billion corners for minutes; here every count is checked
// against the lines the file has.
#pragma once

#include <string>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

Status read_off(const std::string& bytes, PolygonMesh* mesh);

}  // namespace srcodec
