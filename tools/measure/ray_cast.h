// Orthographic renders of a mesh by ray casting (Intel's Embree): the frame
// they are made in, the views, and a view cast into per-pixel depths and
// normals. The visual measure (visual_difference.h) compares such renders;
// `srcodec render` (shaded_render.h) shades them into pictures.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "format/status.h"
#include "remesh/surface_distance.h"

namespace srcodec {

// The frame every render is made in: a mesh's bounding-box centre and half
// diagonal map to the origin and 1, so that Embree's single precision is
// spent on the shape and not on its offset.
struct RenderFrame {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;
  Eigen::Vector3d to_unit(const Eigen::Vector3d& p) const { return (p - center) / radius; }
};

// The frame of the surface's faces of positive area.
RenderFrame bounding_frame(const MeasuredSurface& surface);

// An orthographic view looking along -direction, the image spanned by u
// (rightwards) and v (upwards); it covers [-1, 1]^2 of the frame.
struct View {
  Eigen::Vector3d direction, u, v;
};

// The view from unit `direction` (from the centre towards the viewer) with
// `up` (not along it) showing upwards.
View view_along(const Eigen::Vector3d& direction, const Eigen::Vector3d& up);

// One view per unit direction, z upwards (x for directions near the z axis).
std::vector<View> views_from(const std::vector<Eigen::Vector3d>& directions);

// Directions spread evenly over the sphere (a Fibonacci lattice), unit
// vectors from the centre towards the viewer, none at the poles.
std::vector<Eigen::Vector3d> view_directions(int views);

// What one pixel of a render shows: the depth (along the view, from the
// plane through the frame's centre, in the frame's units) and the unit
// normal of the triangle hit, in its own orientation, or nothing.
struct Pixel {
  float depth = std::numeric_limits<float>::quiet_NaN();  // NaN: the ray misses
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  bool covered() const { return !std::isnan(depth); }
};

// Receives row `index` (view * resolution + y, y = 0 at the bottom of the
// view) of a render, `resolution` pixels from left to right.
using RowSink = std::function<void(size_t index, const std::vector<Pixel>& pixels)>;

// An Embree device: renders any number of meshes, one after the other or
// from several threads. Copies share the device.
class RayCaster {
 public:
  // Fails with kInternal when Embree cannot start.
  static StatusOr<RayCaster> start();

  // Casts one ray per pixel of every view at `resolution` pixels a side
  // into `surface`'s faces, in `frame`; rows run in parallel, each given to
  // `row` once. Fails with kInternal when Embree cannot build the scene.
  Status render(const MeasuredSurface& surface, const RenderFrame& frame, const std::vector<View>& views,
                int resolution, const RowSink& row) const;

 private:
  struct Device;
  explicit RayCaster(std::shared_ptr<const Device> device) : device_(std::move(device)) {}
  std::shared_ptr<const Device> device_;
};

}  // namespace srcodec
