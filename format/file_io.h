// Whole-file reads and safe writes.
#pragma once

#include <cstdint>
#include <string>

#include "format/status.h"

namespace srcodec {

// OK when `path` names a file (not a folder) in a folder that exists: lets a
// long computation fail before it starts rather than at the end.
Status check_output_path(const std::string& path);

// Writes `bytes` to a temporary file in the target's folder and renames it
// over `path`: readers never see a partial file, and on failure whatever was
// at `path` before is left as it was.
Status write_file_atomically(const std::string& path, const std::string& bytes);

// The whole file, or a clear error (missing, unreadable, larger than max_bytes).
StatusOr<std::string> read_file_bytes(const std::string& path, uint64_t max_bytes = uint64_t{1} << 34);

}  // namespace srcodec
