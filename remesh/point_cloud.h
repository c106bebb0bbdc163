// nanoflann's view of a vector of 3D points, and the k-d tree over it, as
// the remesher's stages use them (nearest sites, nearest input vertices).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <nanoflann.hpp>
#include <vector>

namespace srcodec {

struct PointCloud {
  const std::vector<Eigen::Vector3d>& points;
  size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return points[i][static_cast<Eigen::Index>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

using PointTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, PointCloud>, PointCloud, 3, uint32_t>;

}  // namespace srcodec
