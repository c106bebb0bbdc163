// The PSNR of a cut of an embedded stream, estimated instead of measured:
// rate control tries a dozen cuts or more, and measuring each with the
// metric (remesh/surface_distance.h) costs two searches over hundreds of
// thousands of samples, where this costs one pass over the triangles.
//
// A cut decodes to the whole stream's mesh (the same connectivity: the cut
// keeps the refinement flags) with each vertex displaced by the details it
// lacks. Its squared error against the input is taken as the whole stream's
// (measured once) plus the mean square of that displacement over the
// surface: the remesh's error and the coding's are independent, so their
// squares add. Only the displacement across the surface counts (along it,
// the surface stays where it was); it is linear over each triangle, so its
// mean square there is exact (the P1 finite-element mass matrix).
// docs/codec_design.md ("How the knee is found") compares it with the metric.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "remesh/surface_distance.h"

namespace srcodec {

class CutEstimate {
 public:
  // `whole`: the whole stream decoded; `measured`: the metric's figures of
  // it against the input (its RMS, and the diagonal that scales the PSNR).
  // Keeps what psnr() needs of `whole`.
  CutEstimate(const TriangleMesh& whole, const SurfaceDistance& measured);

  // The estimated PSNR of `cut`, the decode of a cut of the same stream.
  // kInvalidArgument when it does not have whole's vertices and triangles
  // (a cut inside the refinement flags), for the caller to measure instead.
  StatusOr<double> psnr(const TriangleMesh& cut) const;
  // The whole stream's PSNR, as measured.
  double whole_psnr() const { return whole_psnr_; }

 private:
  std::vector<Eigen::Vector3d> positions_;
  std::vector<std::array<int32_t, 3>> triangles_;
  std::vector<Eigen::Vector3d> unit_normals_;  // per triangle; zero for no area
  std::vector<double> area_share_;             // per triangle: its share of the total area
  double whole_squared_ = 0.0;
  double whole_psnr_ = 0.0;
  double diag_ = 0.0;
};

}  // namespace srcodec
