// A pass over text mesh files (OBJ, ascii PLY, ascii STL) before they are
// parsed. OpenMesh's OBJ reader skips a vertex line it cannot read, so later
// indices point at the wrong vertices: a silent wrong result. Our PLY reader
// would only say it ran out of numbers. Here every coordinate must be a
// finite number, and the error names the line.
#pragma once

#include <string>

#include "format/status.h"

namespace srcodec {

// `ext` is ".obj", ".ply" or ".stl"; binary PLY/STL and OFF (whose reader
// checks its own numbers) pass untouched.
Status check_text_numbers(const std::string& bytes, const std::string& ext);

}  // namespace srcodec
