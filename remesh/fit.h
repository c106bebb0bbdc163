// The fit (ours, not in the paper): the remesh's vertices leave the input's
// vertices for the places that bring its triangles closest to the input
// surface, each along its normal.
//
// The paper's sites are input vertices, so every triangle of the remesh is a
// chord of the input: on a convex part the whole triangle lies inside the
// surface, and the error is one-sided. Moving a vertex along its normal by
// the mean signed distance of the input around it centres the triangles on
// the surface (in 1D this divides the RMS of a chord's error by 2.4).
//
// The distance is measured both ways, as the metric (`srcodec compare`)
// measures it: from samples of the input to the remesh, and from points of
// the remesh's triangles to the input. The metric's PSNR is the worse of the
// two ways; the input's samples alone leave out the parts of the remesh that
// no sample is nearest to, and the fit would not pull them in.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "format/mesh.h"
#include "remesh/folds.h"
#include "remesh/nearest_triangle.h"
#include "remesh/point_cloud.h"

namespace srcodec {

struct FitOptions {
  int iterations = 3;
  double step = 0.9;              // the part of the mean signed distance a vertex moves by, per iteration
  size_t samples_per_vertex = 4;  // input surface samples, spread by area
  // The weight of the remesh's points measured to the input against the
  // input's samples measured to the remesh, per unit of area (0: the input's
  // samples alone).
  double remesh_weight = 2.0;
  uint64_t seed = 1;
};

struct FitReport {
  size_t moved = 0;    // vertices moved in the last iteration
  size_t refused = 0;  // moves undone because a triangle of some level would turn, fold or pleat, summed
  double mean_offset = 0.0;  // mean |move| of the moved vertices in the last iteration
  // The finest level after the fit: triangles facing against the input
  // (corners judged by the nearest vertex of `sides`, as
  // RefineLevelReport::folded_by_nearest_input) and pleats (as
  // RefineLevelReport::pleats). The fit's check keeps the first from
  // growing; the second is only counted.
  size_t folded_by_nearest_input = 0;
  size_t pleats = 0;
  double seconds = 0.0;
};

// Moves each vertex of `levels.back()` (triangles over `positions`) that is
// not `fixed` along its unit normal by `step` times the weighted mean signed
// distance to it of samples of `input`'s surface, each sample given to its
// nearest triangle and shared among that triangle's corners by the
// barycentric coordinates of its nearest point there, and of four points of
// each triangle to their nearest points of `input`, shared among its corners
// alike (weighted by FitOptions::remesh_weight). A move is undone when it
// would turn a triangle of any level in `levels` by 60 degrees or more, or
// make it face against the input: judged, as the fold recount does, by the
// normals of the vertices of `sides` (the oversampled input the remesher ran
// on) nearest its corners. `input_search`, when given, is an exact search
// (NearestTriangle with exact_search) over `input` for the remesh's points;
// without it the fit builds one.
FitReport fit_to_surface(const TriangleMesh& input, const TriangleMesh& sides,
                         const std::vector<std::vector<std::array<int32_t, 3>>>& levels, const std::vector<char>& fixed,
                         std::vector<Eigen::Vector3d>* positions, const FitOptions& options = {},
                         const NearestTriangle* input_search = nullptr);

}  // namespace srcodec
