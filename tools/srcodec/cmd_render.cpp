// `srcodec render REF A B ... -o OUT.png`: the meshes side by side in one
// picture, every panel the same view framing the first mesh
// (tools/measure/shaded_render.h), to see what a file looks like beside its
// input and another codec's file.
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "format/file_io.h"
#include "format/mesh_files/mesh_io.h"
#include "tools/measure/ray_cast.h"
#include "tools/measure/shaded_render.h"
#include "tools/srcodec/commands.h"

namespace srcodec {
namespace {

constexpr int kChoosableViews = 16;  // --view picks one of the visual measure's default views

struct RenderCliOptions {
  std::vector<std::string> meshes;
  std::string output;
  int view = 0;
  std::string direction, up;
  ShadedRenderOptions render;
};

// "x,y,z": three finite numbers.
std::optional<Eigen::Vector3d> vector_of(const std::string& text) {
  Eigen::Vector3d v;
  std::istringstream parts(text);
  std::string part;
  int n = 0;
  for (; std::getline(parts, part, ','); ++n)
    if (n == 3 || !command_line_detail::parse_value(part, v[n]).empty() || !std::isfinite(v[n])) return std::nullopt;
  if (n != 3 || text.back() == ',') return std::nullopt;
  return v;
}

Status run_render(const RenderCliOptions& o) {
  if (file_extension(o.output) != ".png") return invalid_argument(o.output + ": the output must be a .png file");
  SRCODEC_RETURN_IF_ERROR(check_output_path(o.output));
  ShadedRenderOptions options = o.render;
  options.direction = o.direction.empty() ? view_directions(kChoosableViews)[o.view] : *vector_of(o.direction);
  if (!o.up.empty()) options.up = *vector_of(o.up);
  std::vector<TriangleMesh> meshes;
  for (const std::string& path : o.meshes) {
    SRCODEC_ASSIGN_OR_RETURN(TriangleMesh mesh, read_triangle_mesh(path));
    meshes.push_back(std::move(mesh));
  }
  SRCODEC_ASSIGN_OR_RETURN(const GreyImage image, render_side_by_side(meshes, options, o.meshes));
  SRCODEC_RETURN_IF_ERROR(write_grey_png(image, o.output));
  std::printf("%zu panels of %dx%d seen from (%.4g, %.4g, %.4g) -> %s\n", meshes.size(), options.resolution,
              options.resolution, options.direction.x(), options.direction.y(), options.direction.z(),
              o.output.c_str());
  return ok_status();
}

}  // namespace

Command add_render_command(CommandLine& cli) {
  auto o = std::make_shared<RenderCliOptions>();
  Subcommand& cmd = cli.add_command(
      "render", "Render meshes side by side into one PNG, every panel the same view framing the first mesh");
  cmd.positional_list("mesh", o->meshes, "Meshes (OBJ, PLY, OFF, STL), left to right; the first sets the frame");
  cmd.option("-o,--output", o->output, "PNG to write").required();
  auto& view = cmd.option("--view", o->view, "View K of the visual measure's 16 directions (compare --views 16)")
                   .range(0, kChoosableViews - 1)
                   .show_default();
  const auto is_vector = [](const std::string& text) {
    const std::optional<Eigen::Vector3d> v = vector_of(text);
    return v && !v->isZero(0.0);
  };
  cmd.option("--direction", o->direction, "Look from direction X,Y,Z (from the centre towards the viewer)")
      .check(is_vector, "be three numbers X,Y,Z, not all 0", "")
      .excludes(view);
  cmd.option("--up", o->up, "X,Y,Z shows upwards (default: z, or x when looking along z)")
      .check(is_vector, "be three numbers X,Y,Z, not all 0", "");
  cmd.option("--resolution", o->render.resolution, "Pixels per side of each panel")
      .range(kMinRenderResolution, kMaxRenderResolution)
      .show_default();
  return {&cmd, [o] { return run_render(*o); }};
}

}  // namespace srcodec
