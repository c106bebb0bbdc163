// The progress lines of `remesh`, `encode` and `rd`: the text of each step
// remesh/ reports (remesh/progress.h).
#pragma once

#include <functional>
#include <string>

#include "remesh/progress.h"

namespace srcodec {

// One line, without a prefix or newline.
std::string remesh_progress_line(const RemeshProgress& p);
// The line for the input as read and cleaned, before the remesh begins.
std::string read_progress_line(size_t vertices, size_t triangles, double seconds);
// A callback for RemeshOptions::progress that hands each line to `say`.
RemeshProgressCallback remesh_progress_lines(std::function<void(const std::string&)> say);

}  // namespace srcodec
