// Pictures of meshes side by side for a person to compare: `srcodec render`.
// Every panel is the same orthographic view (ray_cast.h) framing the first
// mesh's bounding sphere, so the panels match pixel for pixel, as the visual
// measure's renders do. Shading is flat, per triangle and in its own
// orientation: a triangle turned over shows dark, as in a renderer that
// leaves back faces unlit.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "tools/measure/grey_png.h"

namespace srcodec {

constexpr int kMinRenderResolution = 16, kMaxRenderResolution = 2048;
// The grey line between panels, in pixels.
constexpr int kPanelGap = 2;

struct ShadedRenderOptions {
  int resolution = 512;  // pixels per side of each panel, kMinRenderResolution..kMaxRenderResolution
  // From the centre towards the viewer (any length but 0).
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  // What shows upwards (not along `direction`); by default z, or x for
  // directions near the z axis, as the visual measure's views.
  std::optional<Eigen::Vector3d> up;
};

// The meshes left to right, each in a square panel of `resolution` pixels
// a side, kPanelGap apart. Fails with kInvalidArgument on options out of
// range or no mesh, with kInvalidMesh on a mesh with no area or a bad index
// or coordinate (naming it by `names`, one per mesh, or else "panel N",
// counted from 1), and with kInternal when Embree fails.
StatusOr<GreyImage> render_side_by_side(const std::vector<TriangleMesh>& meshes, const ShadedRenderOptions& options,
                                        const std::vector<std::string>& names = {});

// The column where panel k starts.
inline int panel_left(int k, int resolution) { return k * (resolution + kPanelGap); }

// The grey of a background pixel and of a triangle seen from behind.
constexpr uint8_t kBackgroundGrey = 255, kBackFaceGrey = 31;

}  // namespace srcodec
