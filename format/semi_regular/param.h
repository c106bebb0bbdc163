// A point of the base domain: the parameterization that links the input
// surface, the base mesh and every refined level (MAPS-style, Lee et al. 1998,
// as used by Kammoun, Payan, Antonini §III-A).
#pragma once

#include <cstdint>

#include <Eigen/Core>

namespace srcodec {

// Base triangle `face` and barycentric coordinates in it, weights of the
// triangle's corners in order (each >= 0, summing to 1). A point on a base
// edge or at a base vertex has several valid descriptions; any one is used.
struct ParamPoint {
  int32_t face = -1;
  Eigen::Vector3d bary = Eigen::Vector3d::Zero();
};

}  // namespace srcodec
