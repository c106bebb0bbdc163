// What a person sees differ between a test mesh and its reference, beside
// the surface distance's PSNR (which a crumpled crease or a few turned-over
// triangles barely move). Both meshes are rendered by ray casting (Intel's
// Embree) from a fixed set of views around the reference's bounding sphere,
// and compared pixel by pixel: the angle between the surfaces' normals (what
// shading shows), the pixels where it is large (visible defects), and the
// depth. Apart from the views, the share of the test surface's area that
// faces against the reference surface nearest it (triangles turned over:
// dark specks in any renderer), judged by remesh/folds.h's facing().
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "tools/measure/ray_cast.h"  // view_directions: where the views look from

namespace srcodec {

constexpr int kMinVisualViews = 16, kMaxVisualViews = 256;
constexpr int kMinVisualResolution = 16, kMaxVisualResolution = 1024;

struct VisualOptions {
  // Orthographic views from directions spread evenly over the sphere (a
  // Fibonacci lattice), each framing the reference's bounding sphere.
  int views = 16;         // kMinVisualViews..kMaxVisualViews
  int resolution = 256;   // pixels per side of each view, kMinVisualResolution..kMaxVisualResolution
  double defect_degrees = 30.0;  // a pixel whose normals differ by more is a visible defect
};

struct VisualDifference {
  // Over the pixels both meshes cover: the mean angle between their normals
  // (oriented: a triangle turned over shows 180 degrees), in degrees.
  double mean_normal_degrees = 0;
  // Over the pixels either mesh covers: the share whose normals differ by
  // more than defect_degrees, or that only one of them covers (a hole, a
  // spike, a moved silhouette).
  double defect_share = 0;
  // 20 log10(2 r / RMS depth difference) over the pixels both cover that are
  // not defects (where both show the same surface), r the reference's
  // bounding-sphere radius (2 r is its bounding-box diagonal, the surface
  // distance's PSNR scale); +inf when the depths agree.
  double depth_psnr = 0;
  // Of the test surface's area, the share whose triangles face against the
  // reference triangle nearest their centroid.
  double turned_over_share = 0;
  size_t pixels = 0;  // pixels either mesh covers, over all views
};

// The reference's half, built once (its renders and its search) for
// measuring many test meshes against it, as `rd` does. Holds a reference to
// the mesh, which must outlive it. Thread-safe to query once built.
class VisualReference {
 public:
  // Fails with kInvalidArgument on options out of range, with kInvalidMesh
  // as surface_distance() does (remesh/surface_distance.h's
  // measured_surface), and with kInternal when Embree cannot start.
  static StatusOr<VisualReference> build(const TriangleMesh& reference, const VisualOptions& options = {});
  StatusOr<VisualDifference> difference_to(const TriangleMesh& test) const;

  VisualReference(VisualReference&&) noexcept;
  VisualReference& operator=(VisualReference&&) noexcept;
  ~VisualReference();

 private:
  struct State;
  explicit VisualReference(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// VisualReference::build(reference, options) and difference_to(test).
StatusOr<VisualDifference> visual_difference(const TriangleMesh& reference, const TriangleMesh& test,
                                             const VisualOptions& options = {});

}  // namespace srcodec
