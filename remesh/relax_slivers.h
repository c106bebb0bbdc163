// Sliver relaxation (ours, not in the paper): last in the remesh, the
// vertices that only the finest level uses move along their tangent plane
// toward their neighbours' mean where a triangle at them is a sliver.
//
// Slivers are where coding error turns triangles over: a decoded triangle
// that faces against the input is far more often a sliver of the remesh
// than the share of slivers would suggest (docs/remesh_design.md).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "remesh/folds.h"

namespace srcodec {

struct SliverRelaxOptions {
  double poor_quality = 0.5;  // triangles below this quality (triangle_quality) have their corners moved
  // A vertex moves only where the input's sides at it and at its neighbours
  // are within acos(flat_cosine) of each other: across a crease or a thin
  // part, the tangent plane of the remesh is not the input's.
  double flat_cosine = 0.866;
  int rounds = 3;
};

struct SliverRelaxReport {
  size_t poor_before = 0, poor_after = 0;  // finest triangles below poor_quality
  size_t moved = 0;                        // moves kept, over all rounds
  double seconds = 0.0;
};

// 4 sqrt(3) area / (sum of squared edge lengths): 1 for an equilateral
// triangle, 0 for one with no area.
double triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// Moves each vertex of `finest` that `coarser` (the level below's
// triangles) does not use and `fixed` leaves free (0), at a triangle of
// quality below options.poor_quality and at no folded triangle or pleat, to
// its neighbours' mean pressed onto its tangent plane (the normal of its
// triangles). A move is kept when the worst triangle at the vertex gets
// better, every triangle at it faces along the sides of the input (`sides`,
// as the fold count judges) at its corners, and none meets a neighbour at
// more than 150 degrees: no level gets a folded triangle or a pleat more or
// less, and the coarser levels do not change. Vertices in increasing order,
// up to options.rounds rounds while one moves. Deterministic.
SliverRelaxReport relax_slivers(const FoldCounter::Sides& sides, const std::vector<std::array<int32_t, 3>>& finest,
                                const std::vector<std::array<int32_t, 3>>& coarser, const std::vector<char>& fixed,
                                std::vector<Eigen::Vector3d>* positions, const SliverRelaxOptions& options = {});

}  // namespace srcodec
