// A pass over text mesh files (OBJ, OFF, ascii PLY, ascii STL) before they
// reach OpenMesh's parsers, which skip a vertex line they cannot read (OBJ:
// later indices then point at the wrong vertices) or read a stream that has
// failed as zeros (OFF, PLY): both would be silent wrong results. Here every
// coordinate must be a finite number, and the error names the line.
#pragma once

#include <string>

#include "format/status.h"

namespace srcodec {

// `ext` is ".obj", ".off", ".ply" or ".stl"; binary PLY/STL pass untouched.
Status check_text_numbers(const std::string& bytes, const std::string& ext);

}  // namespace srcodec
