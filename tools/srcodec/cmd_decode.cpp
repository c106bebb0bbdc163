// `srcodec decode IN.srm -o OUT.obj [--level L] [--bytes N]`: the mesh of
// level L from the whole file or from its first N bytes, through the public
// decoder (<srcodec/decoder.h>). The OBJ of a file with creases has normals
// split at them (write_mesh with crease edges), so viewers show them sharp.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <srcodec/decoder.h>

#include <algorithm>

#include "format/file_io.h"
#include "format/mesh_files/mesh_io.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"

namespace srcodec {
namespace {

struct DecodeCliOptions {
  std::string input, output;
  int level = -1;
  uint64_t bytes = 0;
  uint64_t max_vertices = uint64_t{1} << 22;
  bool single_thread = false;
  bool json = false;
};

Status run_decode(const DecodeCliOptions& o) {
  SRCODEC_RETURN_IF_ERROR(check_output_path(o.output));
  SRCODEC_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(o.input));
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  DecodeOptions options;
  options.level = o.level;
  options.max_bytes = o.bytes;
  options.max_vertices = o.max_vertices;
  options.threads = !o.single_thread;
  StatusOr<Decoded> decoded = decode(data, bytes.size(), options);
  if (!decoded.ok()) return decoded.status().with_context(o.input);
  SRCODEC_ASSIGN_OR_RETURN(const FileInfo info, inspect(data, bytes.size()));
  SRCODEC_RETURN_IF_ERROR(write_mesh(o.output, decoded->mesh, decoded->crease_edges));
  const uint64_t present = o.bytes > 0 ? std::min<uint64_t>(o.bytes, bytes.size()) : bytes.size();
  const bool crease_normals = !decoded->crease_edges.empty() && keeps_corner_normals(o.output);
  if (o.json) {
    JsonWriter j;
    j.field("input", o.input)
        .field("output", o.output)
        .field("level", decoded->level)
        .field("levels", info.levels)
        .field("vertices", decoded->mesh.vertex_count())
        .field("triangles", decoded->mesh.triangle_count())
        .field("last_complete_plane", decoded->last_complete_plane)
        .field("base_cut", decoded->base_cut)
        .field("crease_edges", decoded->crease_edges.size() / 2)
        .field("creases_cut", decoded->creases_cut)
        .field("crease_normals", crease_normals)
        .field("bytes_used", static_cast<size_t>(decoded->bytes_used))
        .field("bytes_present", static_cast<size_t>(present))
        .field("file_bytes", static_cast<size_t>(info.declared_bytes));
    std::cout << j.str() << "\n";
  } else {
    std::printf("%s: level %d of %d, %zu vertices, %zu triangles, from %llu of %llu bytes -> %s\n", o.input.c_str(),
                decoded->level, info.levels, decoded->mesh.vertex_count(), decoded->mesh.triangle_count(),
                static_cast<unsigned long long>(decoded->bytes_used),
                static_cast<unsigned long long>(info.declared_bytes), o.output.c_str());
    if (crease_normals)
      std::printf("  normals split at its %zu crease edges, so that viewers shade them sharp\n",
                  decoded->crease_edges.size() / 2);
    if (decoded->base_cut)
      std::printf("  the file was cut inside its base mesh: %zu of its %llu triangles decoded\n",
                  decoded->mesh.triangle_count(), static_cast<unsigned long long>(info.base_triangles));
    else if (decoded->creases_cut)
      std::printf("  the file was cut inside its creases: decoded the base mesh (level 0) instead\n");
    else if (o.level >= 0 && decoded->level < o.level)
      std::printf("  the file was cut inside the refinement flags of level %d: decoded level %d instead\n",
                  decoded->level, decoded->level);
  }
  return ok_status();
}

}  // namespace

Command add_decode_command(CommandLine& cli) {
  auto o = std::make_shared<DecodeCliOptions>();
  Subcommand& cmd = cli.add_command("decode", "Decode an .srm file to a mesh, at any level, from any prefix");
  cmd.positional("file", o->input, "The .srm file");
  cmd.option("-o,--output", o->output,
             "Mesh to write (OBJ, PLY, OFF, STL by extension). A file with creases: an OBJ gets normals that keep them "
             "sharp (vn lines, split at the crease edges); PLY, OFF and STL are written without normals per corner")
      .required();
  cmd.option("--level", o->level, "Level to decode: 0 is the base mesh (default: the finest)").range(0, 12);
  cmd.option("--bytes", o->bytes, "Decode from the first N bytes only").positive();
  cmd.option("--max-vertices", o->max_vertices, "Refuse files that decode to more vertices than this").show_default();
  cmd.flag("--single-thread", o->single_thread, "Decode on one thread (the same mesh; for many decodes side by side)");
  cmd.flag("--json", o->json, "Print one JSON object");
  return {&cmd, [o] { return run_decode(*o); }};
}

}  // namespace srcodec
