// libFuzzer target: mesh file parsing through srcodec's I/O layer, then
// cleaning, as `srcodec info` and `encode` do.
//   byte 0: the format, by the extension it selects (byte % 4):
//           .obj .off .ply .stl
//   the rest: the file's bytes.
// read_polygon_mesh takes a path (OBJ and STL go through OpenMesh's readers,
// which read files), so the bytes are written to a temporary file, one per
// process, and read back from there.
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "format/mesh_files/mesh_clean.h"
#include "format/mesh_files/mesh_io.h"

namespace {

constexpr const char* kExtensions[] = {".obj", ".off", ".ply", ".stl"};

// Built once and never destroyed: remove_temp_files runs at exit, after
// the destructors of function-local statics made later than its atexit.
const std::string& temp_path(int format) {
  static const auto* paths = [] {
    const std::string base =
        (std::filesystem::temp_directory_path() / ("srcodec_mesh_read_fuzzer_" + std::to_string(getpid()))).string();
    auto* p = new std::array<std::string, 4>;
    for (int f = 0; f < 4; ++f) (*p)[f] = base + kExtensions[f];
    return p;
  }();
  return (*paths)[format];
}

void remove_temp_files() {
  for (int f = 0; f < 4; ++f) std::remove(temp_path(f).c_str());
}

bool write_bytes(const std::string& path, const uint8_t* data, size_t size) {
  std::FILE* out = std::fopen(path.c_str(), "wb");
  if (out == nullptr) return false;
  const bool ok = std::fwrite(data, 1, size, out) == size;
  return std::fclose(out) == 0 && ok;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::atexit(remove_temp_files);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const int format = data[0] % 4;
  const std::string& path = temp_path(format);
  if (!write_bytes(path, data + 1, size - 1)) {
    std::perror(path.c_str());
    std::abort();  // the machine, not the input: stop rather than fuzz nothing
  }

  srcodec::StatusOr<srcodec::PolygonMesh> raw = srcodec::read_polygon_mesh(path);
  if (!raw.ok()) return 0;
  srcodec::CleanReport report;
  const srcodec::TriangleMesh mesh = srcodec::clean_mesh(raw.value(), &report);
  // read_polygon_mesh promises indices in range; cleaning must keep them so.
  const auto n = static_cast<int64_t>(mesh.positions.size());
  for (const auto& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= n) __builtin_trap();
    }
  }
  return 0;
}
