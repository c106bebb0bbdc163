// `srcodec info MESH`: what the file holds as read, and after srcodec's cleaning.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>

#include "format/mesh_files/mesh_io.h"
#include "format/mesh_files/mesh_stats.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"

namespace srcodec {
namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
};

void add_stats(JsonWriter& j, const MeshStats& s) {
  j.field("vertices", s.vertices)
      .field("referenced_vertices", s.referenced_vertices)
      .field("faces", s.faces)
      .field("triangles", s.triangles)
      .field("all_triangles", s.triangles == s.faces)
      .field("max_face_size", s.max_face_size)
      .field("edges", s.edges)
      .field("components", s.components)
      .field("boundary_edges", s.boundary_edges)
      .field("boundary_loops", s.boundary_loops)
      .field("nonmanifold_edges", s.nonmanifold_edges)
      .field("nonmanifold_vertices", s.nonmanifold_vertices)
      .field("orientation_inconsistent_edges", s.orientation_inconsistent_edges)
      .field("degenerate_faces", s.degenerate_faces)
      .field("euler_characteristic", s.euler_characteristic)
      .field("closed", s.is_closed())
      .field("manifold", s.is_manifold());
  if (s.genus) j.field("genus", *s.genus);
  else j.null_field("genus");
  j.field("bbox_diagonal", s.bbox_diagonal);
}

void print_table(const std::string& path, const MeshStats& raw, const MeshStats& clean, const CleanReport& r) {
  std::printf("%s\n", path.c_str());
  std::printf("  %-32s %16s %16s\n", "", "as read", "cleaned");
  auto row = [](const char* name, size_t a, size_t b) { std::printf("  %-32s %16zu %16zu\n", name, a, b); };
  row("vertices", raw.vertices, clean.vertices);
  row("referenced vertices", raw.referenced_vertices, clean.referenced_vertices);
  row("faces", raw.faces, clean.faces);
  row("triangles", raw.triangles, clean.triangles);
  row("largest face (corners)", raw.max_face_size, clean.max_face_size);
  row("edges", raw.edges, clean.edges);
  row("connected components", raw.components, clean.components);
  row("boundary edges", raw.boundary_edges, clean.boundary_edges);
  row("boundary loops", raw.boundary_loops, clean.boundary_loops);
  row("non-manifold edges", raw.nonmanifold_edges, clean.nonmanifold_edges);
  row("non-manifold vertices", raw.nonmanifold_vertices, clean.nonmanifold_vertices);
  row("orientation-inconsistent edges", raw.orientation_inconsistent_edges, clean.orientation_inconsistent_edges);
  row("degenerate faces", raw.degenerate_faces, clean.degenerate_faces);
  std::printf("  %-32s %16ld %16ld\n", "Euler characteristic", raw.euler_characteristic, clean.euler_characteristic);
  auto genus = [](const MeshStats& s) { return s.genus ? std::to_string(*s.genus) : std::string("n/a"); };
  std::printf("  %-32s %16s %16s\n", "genus", genus(raw).c_str(), genus(clean).c_str());
  auto kind = [](const MeshStats& s) {
    return std::string(s.is_closed() ? "closed" : "open") + (s.is_manifold() ? " manifold" : " non-manifold");
  };
  std::printf("  %-32s %16s %16s\n", "surface", kind(raw).c_str(), kind(clean).c_str());
  std::printf("  %-32s %16.6g %16.6g\n", "bounding-box diagonal", raw.bbox_diagonal, clean.bbox_diagonal);
  std::printf("  cleaning: welded %zu coincident vertices, triangulated %zu polygons, dropped %zu degenerate "
              "and %zu duplicate faces and %zu unreferenced vertices, split %zu faces to close zero-area ones\n",
              r.welded_vertices, r.polygons_triangulated, r.degenerate_faces, r.duplicate_faces,
              r.unreferenced_vertices, r.split_faces);
}

// An .srm file is recognized by its first bytes, whatever its name.
bool is_srm_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) && magic[0] == '\x89' && magic[1] == 'S' && magic[2] == 'R' && magic[3] == 'M';
}

Status run_info(const InfoOptions& o) {
  if (is_srm_file(o.path)) return print_srm_info(o.path, o.json);
  SRCODEC_ASSIGN_OR_RETURN(PolygonMesh raw, read_polygon_mesh(o.path));
  CleanReport report;
  const TriangleMesh clean = clean_mesh(raw, &report);
  const MeshStats raw_stats = compute_stats(raw);
  const MeshStats clean_stats = compute_stats(to_polygon_mesh(clean));
  if (o.json) {
    JsonWriter j;
    j.field("file", o.path).field("format", file_extension(o.path).substr(1));
    add_stats(j, raw_stats);
    JsonWriter cleaned;
    add_stats(cleaned, clean_stats);
    JsonWriter cleaning;
    cleaning.field("welded_vertices", report.welded_vertices)
        .field("polygons_triangulated", report.polygons_triangulated)
        .field("degenerate_faces", report.degenerate_faces)
        .field("duplicate_faces", report.duplicate_faces)
        .field("split_faces", report.split_faces)
        .field("unreferenced_vertices", report.unreferenced_vertices);
    j.object("cleaned", cleaned).object("cleaning", cleaning);
    std::cout << j.str() << "\n";
  } else {
    print_table(o.path, raw_stats, clean_stats, report);
  }
  if (clean.triangles.empty()) return invalid_mesh(o.path + ": every face is degenerate");
  return ok_status();
}

}  // namespace

Command add_info_command(CommandLine& cli) {
  auto options = std::make_shared<InfoOptions>();
  Subcommand& cmd = cli.add_command("info", "Print a mesh's size, topology and defects (as read and after cleaning), or an .srm file's header and byte budget");
  cmd.positional("mesh", options->path, "Mesh file (.obj .off .ply .stl) or .srm file");
  cmd.flag("--json", options->json, "Print one JSON object instead of a table");
  return {&cmd, [options] { return run_info(*options); }};
}

}  // namespace srcodec
