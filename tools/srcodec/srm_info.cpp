// `srcodec info FILE.srm`: the header, the levels, and where the bytes go
// (base mesh, creases, flags, and coefficients per level and per bit plane),
// as the public inspect() reads them.
#include <srcodec/decoder.h>

#include <cstdio>
#include <iostream>
#include <vector>

#include "format/file_io.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"

namespace srcodec {
namespace {

using ull = unsigned long long;

void print_json(const std::string& path, const FileInfo& f) {
  std::vector<JsonWriter> levels, planes;
  for (size_t l = 0; l < f.level_info.size(); ++l) {
    JsonWriter j;
    j.field("level", static_cast<int>(l))
        .field("vertices", static_cast<size_t>(f.level_info[l].vertices))
        .field("flag_bytes", static_cast<size_t>(f.level_info[l].flag_bytes))
        .field("coefficient_bytes", static_cast<size_t>(f.level_info[l].coefficient_bytes))
        .field("drawable_from", static_cast<size_t>(f.level_info[l].drawable_from));
    levels.push_back(j);
  }
  for (const FileInfo::Plane& p : f.planes) {
    JsonWriter j;
    j.field("plane", p.plane).field("bytes", static_cast<size_t>(p.bytes)).field("end", static_cast<size_t>(p.end));
    planes.push_back(j);
  }
  JsonWriter j;
  j.field("file", path)
      .field("format", "srm")
      .field("version", f.version)
      .field("raw_planes", f.raw_planes)
      .field("file_bytes", static_cast<size_t>(f.file_bytes))
      .field("declared_bytes", static_cast<size_t>(f.declared_bytes))
      .field("header_bytes", static_cast<size_t>(f.header_bytes))
      .field("base_mesh_bytes", static_cast<size_t>(f.base_bytes))
      .field("crease_bytes", static_cast<size_t>(f.crease_bytes));
  if (f.crease_edges >= 0) {
    j.field("crease_edges", static_cast<size_t>(f.crease_edges));
  } else {
    j.null_field("crease_edges");  // not all present, or damaged
  }
  j.field("input_vertices", static_cast<size_t>(f.input_vertices))
      .field("input_triangles", static_cast<size_t>(f.input_triangles))
      .field("bpv", f.bits_per_vertex)
      .field("base_vertices", static_cast<size_t>(f.base_vertices))
      .field("base_triangles", static_cast<size_t>(f.base_triangles))
      .field("base_bits", f.base_bits)
      .field("quantizer_step", f.quantizer_step)
      .field("top_plane", f.top_plane)
      .array("levels", levels)
      .array("planes", planes);
  std::cout << j.str() << "\n";
}

void print_text(const std::string& path, const FileInfo& f) {
  std::printf("%s: .srm version %d, %llu bytes", path.c_str(), f.version, static_cast<ull>(f.file_bytes));
  if (f.file_bytes < f.declared_bytes)
    std::printf(" (a prefix: the whole file would be %llu)", static_cast<ull>(f.declared_bytes));
  std::printf("\n  input: %llu vertices, %llu triangles, bounding box (%g %g %g)..(%g %g %g); %.3f bpv\n",
              static_cast<ull>(f.input_vertices), static_cast<ull>(f.input_triangles), f.bbox_min[0], f.bbox_min[1],
              f.bbox_min[2], f.bbox_max[0], f.bbox_max[1], f.bbox_max[2], f.bits_per_vertex);
  std::printf("  header %llu bytes; base mesh %llu vertices, %llu triangles, %d-bit grid, %llu bytes\n",
              static_cast<ull>(f.header_bytes), static_cast<ull>(f.base_vertices), static_cast<ull>(f.base_triangles),
              f.base_bits, static_cast<ull>(f.base_bytes));
  if (f.version >= 3) {
    if (f.crease_edges >= 0) {
      std::printf("  creases: %lld base edges, %llu bytes\n", static_cast<long long>(f.crease_edges),
                  static_cast<ull>(f.crease_bytes));
    } else {
      std::printf("  creases: %llu bytes (not all present, or damaged: not counted)\n",
                  static_cast<ull>(f.crease_bytes));
    }
  }
  std::printf("  %5s %10s %11s %18s\n", "level", "vertices", "flag bytes", "coefficient bytes");
  for (size_t l = 0; l < f.level_info.size(); ++l)
    std::printf("  %5zu %10llu %11llu %18llu\n", l, static_cast<ull>(f.level_info[l].vertices),
                static_cast<ull>(f.level_info[l].flag_bytes), static_cast<ull>(f.level_info[l].coefficient_bytes));
  std::printf("  quantizer step %g; bit planes %d..0", f.quantizer_step, f.top_plane);
  if (f.raw_planes > 0) std::printf(" (raw bits below plane %d)", f.raw_planes);
  std::printf(", bytes per plane:");
  for (const FileInfo::Plane& p : f.planes) std::printf(" %llu", static_cast<ull>(p.bytes));
  std::printf("\n");
}

}  // namespace

Status print_srm_info(const std::string& path, bool json) {
  SRCODEC_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(path));
  StatusOr<FileInfo> info = inspect(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  if (!info.ok()) return info.status().with_context(path);
  if (json) {
    print_json(path, info.value());
  } else {
    print_text(path, info.value());
  }
  return ok_status();
}

}  // namespace srcodec
