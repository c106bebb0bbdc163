// Wavefront OBJ reader: `v` lines (the first three numbers; a fourth weight
// or trailing colours are ignored) and `f` lines (corners `i`, `i/t`, `i//n`,
// `i/t/n`; 1-based, negative counts back from the last vertex read). Other
// statements (vt, vn, g, o, s, usemtl, mtllib, l, p, ...) are skipped; a
// backslash at the end of a line continues it.
//
// Used instead of OpenMesh's OBJ reader, which Debian builds with assertions
// that abort the process on some malformed faces (found by fuzz/), and which
// skips unreadable vertex lines so later indices silently shift. Here every
// coordinate and index is checked and an error names its line.
#pragma once

#include <string>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

Status read_obj(const std::string& bytes, PolygonMesh* mesh);

}  // namespace srcodec
