// `srcodec info FILE.srm`: the header, the levels, and where the bytes go
// (base mesh, flags, and coefficients per level and per bit plane).
#include <cstdio>
#include <iostream>
#include <vector>

#include "format/srm/srm_file.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"

namespace srcodec {

Status print_srm_info(const std::string& path, bool json) {
  SrmReadOptions read;
  read.max_level = 0;  // the table says it all; only the base chunk is loaded
  SRCODEC_ASSIGN_OR_RETURN(SrmFile f, read_srm(path, read));
  const SrmHeader& h = f.header;
  std::vector<uint64_t> level_bytes(h.levels + 1, 0), plane_bytes(h.top_plane + 1, 0);
  for (int p = h.top_plane; p >= 0; --p)
    for (int l = 0; l <= h.levels; ++l) {
      // A rate-controlled file's table ends where the encoder cut the stream.
      const size_t index = h.segment_index(p, l);
      const uint64_t n = index < h.segments.size() ? h.segments[index].length : 0;
      level_bytes[l] += n;
      plane_bytes[p] += n;
    }
  std::vector<uint64_t> vertices(h.levels + 1, 0);
  for (int l = 0; l <= h.levels; ++l) vertices[l] = (l ? vertices[l - 1] : 0) + h.level_vertices[l];
  if (json) {
    std::vector<JsonWriter> levels, planes;
    for (int l = 0; l <= h.levels; ++l) {
      JsonWriter j;
      j.field("level", l)
          .field("vertices", static_cast<size_t>(vertices[l]))
          .field("flag_bytes", static_cast<size_t>(l ? h.flags[l - 1].length : 0))
          .field("coefficient_bytes", static_cast<size_t>(level_bytes[l]));
      levels.push_back(j);
    }
    for (int p = h.top_plane; p >= 0; --p) {
      JsonWriter j;
      j.field("plane", p).field("bytes", static_cast<size_t>(plane_bytes[p]));
      planes.push_back(j);
    }
    JsonWriter j;
    j.field("file", path)
        .field("format", "srm")
        .field("version", h.version())
        .field("raw_planes", h.raw_planes)
        .field("file_bytes", static_cast<size_t>(f.file_size))
        .field("declared_bytes", static_cast<size_t>(f.declared_size))
        .field("header_bytes", static_cast<size_t>(f.header_size))
        .field("base_mesh_bytes", static_cast<size_t>(h.base.length))
        .field("input_vertices", static_cast<size_t>(h.input_vertices))
        .field("input_triangles", static_cast<size_t>(h.input_triangles))
        .field("bpv", 8.0 * static_cast<double>(f.file_size) / static_cast<double>(std::max<uint64_t>(h.input_vertices, 1)))
        .field("base_vertices", static_cast<size_t>(h.base_vertices))
        .field("base_triangles", static_cast<size_t>(h.base_triangles))
        .field("base_bits", h.base_bits)
        .field("quantizer_step", h.quant_step)
        .field("top_plane", h.top_plane)
        .array("levels", levels)
        .array("planes", planes);
    std::cout << j.str() << "\n";
    return ok_status();
  }
  std::printf("%s: .srm version %d, %llu bytes", path.c_str(), h.version(), static_cast<unsigned long long>(f.file_size));
  if (f.file_size < f.declared_size)
    std::printf(" (a prefix: the whole file would be %llu)", static_cast<unsigned long long>(f.declared_size));
  std::printf("\n  input: %llu vertices, %llu triangles, bounding box (%g %g %g)..(%g %g %g); %.3f bpv\n",
              static_cast<unsigned long long>(h.input_vertices), static_cast<unsigned long long>(h.input_triangles),
              h.bbox_min.x(), h.bbox_min.y(), h.bbox_min.z(), h.bbox_max.x(), h.bbox_max.y(), h.bbox_max.z(),
              8.0 * static_cast<double>(f.file_size) / static_cast<double>(std::max<uint64_t>(h.input_vertices, 1)));
  std::printf("  header %llu bytes; base mesh %llu vertices, %llu triangles, %d-bit grid, %llu bytes\n",
              static_cast<unsigned long long>(f.header_size), static_cast<unsigned long long>(h.base_vertices),
              static_cast<unsigned long long>(h.base_triangles), h.base_bits,
              static_cast<unsigned long long>(h.base.length));
  std::printf("  %5s %10s %11s %18s\n", "level", "vertices", "flag bytes", "coefficient bytes");
  for (int l = 0; l <= h.levels; ++l)
    std::printf("  %5d %10llu %11llu %18llu\n", l, static_cast<unsigned long long>(vertices[l]),
                static_cast<unsigned long long>(l ? h.flags[l - 1].length : 0),
                static_cast<unsigned long long>(level_bytes[l]));
  std::printf("  quantizer step %g; bit planes %d..0", h.quant_step, h.top_plane);
  if (h.raw_planes > 0)
    std::printf(" (raw bits below plane %d)", h.raw_planes);
  std::printf(", bytes per plane:");
  for (int p = h.top_plane; p >= 0; --p) std::printf(" %llu", static_cast<unsigned long long>(plane_bytes[p]));
  std::printf("\n");
  return ok_status();
}

}  // namespace srcodec
