// STL reader, binary and ASCII. Binary: an 80-byte header, a 32-bit
// triangle count, then 50 bytes per triangle (normal, three corners, an
// attribute word); the count must match the file's length exactly. ASCII:
// `solid`, then `facet ... outer loop, vertex x y z (x3), endloop, endfacet`.
// A file that starts with "solid" but whose length matches its binary count
// is read as binary (some exporters write "solid" into the binary header).
// Corners with identical coordinates become one vertex, as STL repeats every
// corner in each triangle that uses it.
#pragma once

#include <string>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

Status read_stl(const std::string& bytes, PolygonMesh* mesh);

}  // namespace srcodec
