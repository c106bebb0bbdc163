#include "tools/measure/shaded_render.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "remesh/surface_distance.h"
#include "tools/measure/ray_cast.h"

namespace srcodec {
namespace {

constexpr uint8_t kGapGrey = 200;
// Lambert shading: a headlight (from the viewer) and a key light from the
// upper left, in front; never white, so that a silhouette shows against the
// background. The ambient term alone is what a back face gets.
constexpr double kAmbient = kBackFaceGrey / 255.0, kHeadlight = 0.48, kKeyLight = 0.40;

Status check_options(const ShadedRenderOptions& o, size_t meshes) {
  if (meshes == 0) return invalid_argument("shaded render: no mesh to render");
  if (o.resolution < kMinRenderResolution || o.resolution > kMaxRenderResolution)
    return invalid_argument("shaded render: resolution must be " + std::to_string(kMinRenderResolution) + ".." +
                            std::to_string(kMaxRenderResolution) + ", got " + std::to_string(o.resolution));
  if (!o.direction.allFinite() || !(o.direction.norm() > 0.0))
    return invalid_argument("shaded render: the view direction must be a finite vector other than 0");
  if (o.up && !(o.up->allFinite() && o.up->cross(o.direction.normalized()).norm() > 1e-6 * o.up->norm()))
    return invalid_argument("shaded render: the up direction must be finite and not along the view direction");
  return ok_status();
}

View view_of(const ShadedRenderOptions& o) {
  const Eigen::Vector3d d = o.direction.normalized();
  return o.up ? view_along(d, *o.up) : views_from({d}).front();
}

uint8_t shade(const Eigen::Vector3d& normal, const View& view, const Eigen::Vector3d& key) {
  const double facing = normal.dot(view.direction);
  if (!(facing > 0.0)) return kBackFaceGrey;
  const double light = kAmbient + kHeadlight * facing + kKeyLight * std::max(0.0, normal.dot(key));
  return static_cast<uint8_t>(std::lround(255.0 * std::min(light, 1.0)));
}

}  // namespace

StatusOr<GreyImage> render_side_by_side(const std::vector<TriangleMesh>& meshes, const ShadedRenderOptions& options,
                                        const std::vector<std::string>& names) {
  SRCODEC_RETURN_IF_ERROR(check_options(options, meshes.size()));
  if (!names.empty() && names.size() != meshes.size())
    return invalid_argument("shaded render: " + std::to_string(names.size()) + " names for " +
                            std::to_string(meshes.size()) + " meshes");
  const int res = options.resolution;
  const int panels = static_cast<int>(meshes.size());
  GreyImage image(panel_left(panels, res) - kPanelGap, res, kBackgroundGrey);
  for (int k = 1; k < panels; ++k)
    for (int y = 0; y < res; ++y)
      for (int x = panel_left(k, res) - kPanelGap; x < panel_left(k, res); ++x) image.at(x, y) = kGapGrey;

  const std::vector<View> views = {view_of(options)};
  const View& view = views.front();
  const Eigen::Vector3d key = (-0.5 * view.u + 0.7 * view.v + 0.5 * view.direction).normalized();
  SRCODEC_ASSIGN_OR_RETURN(const RayCaster caster, RayCaster::start());
  RenderFrame frame;
  for (int k = 0; k < panels; ++k) {
    const std::string role = names.empty() ? "panel " + std::to_string(k + 1) : names[k];
    SRCODEC_ASSIGN_OR_RETURN(const MeasuredSurface surface, measured_surface(meshes[k], role.c_str()));
    if (k == 0) frame = bounding_frame(surface);
    // Rows count upwards from the bottom of the view, the image's downwards.
    const auto paint_row = [&](size_t row, const std::vector<Pixel>& pixels) {
      const int y = res - 1 - static_cast<int>(row);
      for (int x = 0; x < res; ++x)
        if (pixels[x].covered())
          image.at(panel_left(k, res) + x, y) = shade(pixels[x].normal.cast<double>(), view, key);
    };
    SRCODEC_RETURN_IF_ERROR(caster.render(surface, frame, views, res, paint_row));
  }
  return image;
}

}  // namespace srcodec
