// `srcodec subdivide MESH -o OUT`: Butterfly, Loop or linear subdivision, per
// component (the remesher's oversampling step on its own; benchmarks use it to
// make large inputs, e.g. igea after two Loop steps).
#include <cstdio>
#include <memory>

#include "format/mesh_files/mesh_io.h"
#include "remesh/components.h"
#include "remesh/oversample.h"
#include "tools/srcodec/commands.h"

namespace srcodec {
namespace {

struct SubdivideOptions {
  std::string input, output, scheme = "loop";
  int steps = 1;
};

Status run_subdivide(const SubdivideOptions& o) {
  SRCODEC_ASSIGN_OR_RETURN(const OversampleScheme scheme, parse_oversample_scheme(o.scheme, "--scheme"));
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh input, read_triangle_mesh(o.input));
  SRCODEC_ASSIGN_OR_RETURN(std::vector<ComponentMesh> parts, split_into_manifold_components(input));
  TriangleMesh out;
  for (const ComponentMesh& part : parts) {
    SRCODEC_ASSIGN_OR_RETURN(TriangleMesh fine, oversample(part.mesh, scheme, o.steps));
    append_mesh(out, fine);
  }
  SRCODEC_RETURN_IF_ERROR(write_mesh(out, o.output));
  std::printf("%s: %zu vertices, %zu triangles -> %s: %zu vertices, %zu triangles\n", o.input.c_str(),
              input.positions.size(), input.triangles.size(), o.output.c_str(), out.positions.size(),
              out.triangles.size());
  return ok_status();
}

}  // namespace

Command add_subdivide_command(CommandLine& cli) {
  auto o = std::make_shared<SubdivideOptions>();
  Subcommand& cmd = cli.add_command("subdivide", "Butterfly, Loop or linear subdivision of every component");
  cmd.positional("mesh", o->input, "Input mesh (OBJ, PLY, OFF, STL)");
  cmd.option("-o,--output", o->output, "Output mesh (OBJ or PLY)").required();
  cmd.option("--scheme", o->scheme, "butterfly, loop or linear").show_default();
  cmd.option("--steps", o->steps, "1-to-4 steps").range(1, 3).show_default();
  return {&cmd, [o] { return run_subdivide(*o); }};
}

}  // namespace srcodec
