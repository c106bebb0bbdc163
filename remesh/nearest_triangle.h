// The triangle of a mesh nearest a point, found among the triangles whose
// centroids are nearest it (a k-d tree over the centroids): exact where
// neighbouring triangles are of about one size, as on the remesh and on
// scans. The fit (remesh/fit.h) and the measured coarsening
// (remesh/measured_coarsening.h) search with it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "remesh/geometry.h"
#include "remesh/point_cloud.h"

namespace srcodec {

class NearestTriangle {
 public:
  using Hit = TriangleHit;

  // Keeps references to both: they must outlive this and not change. With
  // `exact_search`, also builds what exact() needs.
  NearestTriangle(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<int32_t, 3>>& triangles,
                  bool exact_search = false);
  NearestTriangle(const NearestTriangle&) = delete;
  NearestTriangle& operator=(const NearestTriangle&) = delete;

  // The nearest among the 10 triangles with the nearest centroids; on a tie
  // the one whose centroid is nearer. Thread-safe.
  Hit operator()(const Eigen::Vector3d& q) const;
  // The nearest of all (needs exact_search; else as operator()). The
  // slivers of an irregular input can lie nearer than the 10 nearest
  // centroids' triangles, and to points far from the surface they often do,
  // which puts the remesh's error toward the input too high. Each triangle is covered by points (the centroids of a
  // regular split of it) within `reach_` of all of it, so that every
  // triangle holding a point nearer than d has one of them within d + reach_;
  // a few very long ones are measured one by one instead.
  // `near_triangle`, when not -1, is a triangle likely to be the nearest (a
  // neighbouring query's): the search starts from it instead of from the
  // nearest centroids. The answer is the same either way; only the time
  // differs.
  Hit exact(const Eigen::Vector3d& q, int32_t near_triangle = -1) const;

 private:
  const std::vector<Eigen::Vector3d>& positions_;
  const std::vector<std::array<int32_t, 3>>& triangles_;
  std::vector<Eigen::Vector3d> centroids_;
  PointCloud cloud_;
  PointTree tree_;
  // exact_search: the covering points, their triangles, and their reach;
  // the few triangles too long to cover, measured one by one.
  std::vector<Eigen::Vector3d> cover_;
  std::vector<int32_t> cover_triangle_;
  double reach_ = 0.0;
  std::vector<int32_t> loose_;
  PointCloud cover_cloud_;
  PointTree cover_tree_;
};

}  // namespace srcodec
