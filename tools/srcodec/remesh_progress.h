// The progress lines of `remesh`, `encode` and `rd`: the text of each step
// remesh/ reports (remesh/progress.h).
#pragma once

#include <functional>
#include <string>

#include "format/mesh.h"
#include "format/status.h"
#include "remesh/progress.h"

namespace srcodec {

// One line, without a prefix or newline.
std::string remesh_progress_line(const RemeshProgress& p);
// read_triangle_mesh; unless `quiet`, then says on stderr, after `prefix`
// ("encode: "), what was read and cleaned and how long it took.
StatusOr<TriangleMesh> read_mesh_with_progress(const std::string& path, bool quiet, const std::string& prefix);
// A callback for RemeshOptions::progress that hands each line to `say`.
RemeshProgressCallback remesh_progress_lines(std::function<void(const std::string&)> say);

}  // namespace srcodec
