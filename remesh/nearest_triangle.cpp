#include "remesh/nearest_triangle.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "remesh/geometry.h"

namespace srcodec {
namespace {

std::vector<Eigen::Vector3d> centroids(const std::vector<Eigen::Vector3d>& x,
                                       const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<Eigen::Vector3d> out(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) out[t] = (x[triangles[t][0]] + x[triangles[t][1]] + x[triangles[t][2]]) / 3.0;
  return out;
}

Eigen::Vector3d closest_point(const Eigen::Vector3d& q, const std::vector<Eigen::Vector3d>& x,
                              const std::array<int32_t, 3>& t) {
  return closest_on_triangle(q, x[t[0]], x[t[1]], x[t[2]]);
}

}  // namespace

NearestTriangle::NearestTriangle(const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<std::array<int32_t, 3>>& triangles, bool exact_search)
    : positions_(positions),
      triangles_(triangles),
      centroids_(centroids(positions, triangles)),
      cloud_{centroids_},
      tree_(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10)),
      cover_cloud_{cover_},
      cover_tree_(3, cover_cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
  tree_.buildIndex();
  if (!exact_search || triangles.empty()) return;
  // Split each triangle n x n, its longest edge over n at most the median
  // edge: a sub-triangle's centroid is within 2/3 of its longest edge of
  // all of it.
  std::vector<double> longest(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    longest[t] = std::max({(positions[tri[1]] - positions[tri[0]]).norm(), (positions[tri[2]] - positions[tri[1]]).norm(),
                           (positions[tri[0]] - positions[tri[2]]).norm()});
  }
  std::vector<double> sorted = longest;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double edge = sorted[sorted.size() / 2];
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const int n = edge > 0.0 ? std::clamp(static_cast<int>(std::ceil(longest[t] / edge)), 1, 64) : 1;
    reach_ = std::max(reach_, 2.0 / 3.0 * longest[t] / n);
    for_each_subtriangle_centroid(positions[tri[0]], positions[tri[1]], positions[tri[2]], n,
                                  [&](const Eigen::Vector3d& p) {
                                    cover_.push_back(p);
                                    cover_triangle_.push_back(static_cast<int32_t>(t));
                                  });
  }
  cover_tree_.buildIndex();
}

NearestTriangle::Hit NearestTriangle::operator()(const Eigen::Vector3d& q) const {
  constexpr size_t kNear = 10;
  std::array<uint32_t, kNear> idx{};
  std::array<double, kNear> d2{};
  Hit hit;
  if (triangles_.empty()) return hit;
  const size_t k = tree_.knnSearch(q.data(), kNear, idx.data(), d2.data());
  for (size_t j = 0; j < k; ++j) {
    const Eigen::Vector3d c = closest_point(q, positions_, triangles_[idx[j]]);
    const double d = (c - q).squaredNorm();
    if (d < hit.squared) hit = Hit{static_cast<int32_t>(idx[j]), c, d};
  }
  return hit;
}

NearestTriangle::Hit NearestTriangle::exact(const Eigen::Vector3d& q) const {
  Hit hit = (*this)(q);
  if (hit.triangle < 0 || cover_.empty()) return hit;
  const double bound = std::sqrt(hit.squared) + reach_;
  std::vector<std::pair<uint32_t, double>> within;
  nanoflann::SearchParams params;
  params.sorted = false;
  cover_tree_.radiusSearch(q.data(), bound * bound, within, params);
  std::sort(within.begin(), within.end());  // by covering point: the same order whatever the tree's
  int32_t last = -1;
  for (const auto& [k, d2] : within) {
    const int32_t t = cover_triangle_[k];
    if (t == last || std::sqrt(d2) - reach_ >= std::sqrt(hit.squared)) continue;
    last = t;
    const Eigen::Vector3d c = closest_point(q, positions_, triangles_[t]);
    const double d = (c - q).squaredNorm();
    if (d < hit.squared || (d == hit.squared && t < hit.triangle)) hit = Hit{t, c, d};
  }
  return hit;
}

}  // namespace srcodec
