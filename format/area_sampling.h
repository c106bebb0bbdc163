// A point uniform in area over a triangle, from our own generator (Osada et
// al. 2002): (1 - sqrt(r1)) a + sqrt(r1) (1 - r2) b + sqrt(r1) r2 c. The
// metric's samples and the remesher's fit draw theirs with it.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "format/split_mix64.h"

namespace srcodec {

inline Eigen::Vector3d point_in_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                         SplitMix64& rng) {
  const double r1 = std::sqrt(rng.uniform());
  const double r2 = rng.uniform();
  return (1 - r1) * a + (r1 * (1 - r2)) * b + (r1 * r2) * c;
}

}  // namespace srcodec
