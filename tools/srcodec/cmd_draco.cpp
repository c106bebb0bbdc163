// `srcodec draco MESH --qp N`: Draco round trip, the baseline of every comparison.
#include <cstdio>
#include <iostream>
#include <memory>

#include "format/file_io.h"
#include "format/mesh_files/mesh_io.h"
#include "format/mesh_files/mesh_stats.h"
#include "tools/measure/draco_baseline.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"

namespace srcodec {
namespace {

struct DracoCommandOptions {
  std::string mesh;
  DracoOptions draco;
  std::string encoded_path;
  std::string decoded_path;
  bool json = false;
};

Status run_draco(const DracoCommandOptions& o) {
  SRCODEC_ASSIGN_OR_RETURN(PolygonMesh raw, read_polygon_mesh(o.mesh));
  const TriangleMesh mesh = clean_mesh(raw);
  if (mesh.triangles.empty()) return invalid_mesh(o.mesh + ": every face is degenerate");
  // Rates are per vertex of the input as the user has it (referenced ones).
  const size_t input_vertices = compute_stats(raw).referenced_vertices;

  SRCODEC_ASSIGN_OR_RETURN(DracoRoundTrip r, draco_round_trip(mesh, o.draco));
  if (!o.encoded_path.empty()) SRCODEC_RETURN_IF_ERROR(write_file_atomically(o.encoded_path, r.encoded));
  if (!o.decoded_path.empty()) SRCODEC_RETURN_IF_ERROR(write_mesh(r.decoded, o.decoded_path));

  const double bpv = 8.0 * static_cast<double>(r.encoded.size()) / static_cast<double>(input_vertices);
  if (o.json) {
    JsonWriter j;
    j.field("mesh", o.mesh)
        .field("qp", o.draco.quantization_bits)
        .field("cl", o.draco.compression_level)
        .field("bytes", r.encoded.size())
        .field("input_vertices", input_vertices)
        .field("bpv", bpv)
        .field("encode_ms", r.encode_ms)
        .field("decode_ms", r.decode_ms)
        .field("decoded_vertices", r.decoded.positions.size())
        .field("decoded_triangles", r.decoded.triangles.size());
    std::cout << j.str() << "\n";
  } else {
    std::printf("draco qp %d cl %d: %zu bytes, %.3f bits per input vertex (%zu vertices), encode %.2f ms, decode %.2f ms\n",
                o.draco.quantization_bits, o.draco.compression_level, r.encoded.size(), bpv, input_vertices,
                r.encode_ms, r.decode_ms);
  }
  return ok_status();
}

}  // namespace

Command add_draco_command(CommandLine& cli) {
  auto o = std::make_shared<DracoCommandOptions>();
  Subcommand& cmd = cli.add_command("draco", "Encode and decode a mesh with Draco (the baseline)");
  cmd.positional("mesh", o->mesh, "Mesh file");
  cmd.option("--qp", o->draco.quantization_bits, "Position quantization bits").range(1, 30).required();
  cmd.option("--cl", o->draco.compression_level, "Compression level 0..10").range(0, 10).show_default();
  cmd.option("-o,--output", o->encoded_path, "Write the .drc bytes here");
  cmd.option("--decoded", o->decoded_path, "Write Draco's decoded mesh here (.obj or .ply)");
  cmd.flag("--json", o->json, "Print one JSON object");
  return {&cmd, [o] { return run_draco(*o); }};
}

}  // namespace srcodec
