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
  // A triangle more than kMaxSplit median edges long (a sliver across the
  // mesh, as in damaged inputs) would widen every search by its reach; the
  // few there are are measured one by one in exact() instead. Many of them
  // (a mesh of long thin triangles) are covered like the others.
  constexpr double kMaxSplit = 64.0;
  constexpr size_t kMaxLoose = 64;
  const auto splits = [&](size_t t) { return edge > 0.0 ? std::ceil(longest[t] / edge) : 1.0; };
  for (size_t t = 0; t < triangles.size(); ++t)
    if (splits(t) > kMaxSplit) loose_.push_back(static_cast<int32_t>(t));
  if (loose_.size() > kMaxLoose) loose_.clear();
  std::vector<char> loose(triangles.size(), 0);
  for (int32_t t : loose_) loose[t] = 1;
  for (size_t t = 0; t < triangles.size(); ++t) {
    if (loose[t]) continue;
    const auto& tri = triangles[t];
    const int n = static_cast<int>(std::clamp(splits(t), 1.0, kMaxSplit));
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

NearestTriangle::Hit NearestTriangle::exact(const Eigen::Vector3d& q, int32_t near_triangle) const {
  Hit hit;
  const bool prepared = !cover_.empty() || !loose_.empty();
  if (near_triangle >= 0 && static_cast<size_t>(near_triangle) < triangles_.size() && prepared) {
    const Eigen::Vector3d c = closest_point(q, positions_, triangles_[near_triangle]);
    hit = Hit{near_triangle, c, (c - q).squaredNorm()};
  } else {
    hit = (*this)(q);
  }
  if (hit.triangle < 0 || !prepared) return hit;
  for (int32_t t : loose_) {
    const Eigen::Vector3d c = closest_point(q, positions_, triangles_[t]);
    const double d = (c - q).squaredNorm();
    if (d < hit.squared || (d == hit.squared && t < hit.triangle)) hit = Hit{t, c, d};
  }
  if (cover_.empty()) return hit;
  // The covering points within the distance to the nearest triangle found
  // so far plus reach_, that bound shrinking as nearer triangles turn up. A
  // triangle whose covering point lies farther than that cannot be nearer.
  // The nearest, with ties to the lower triangle, whatever the tree's order.
  struct Shrinking {
    const NearestTriangle& self;
    const Eigen::Vector3d& q;
    Hit& hit;
    double bound2;
    // The last triangles tried: a large one has many covering points.
    std::array<int32_t, 8> seen{-1, -1, -1, -1, -1, -1, -1, -1};
    size_t next = 0;
    size_t size() const { return 0; }
    bool full() const { return true; }
    double worstDist() const { return bound2; }
    bool addPoint(double d2, uint32_t k) {
      const int32_t t = self.cover_triangle_[k];
      if (std::sqrt(d2) - self.reach_ >= std::sqrt(hit.squared)) return true;
      if (std::find(seen.begin(), seen.end(), t) != seen.end()) return true;
      seen[next++ % seen.size()] = t;
      const Eigen::Vector3d c = closest_point(q, self.positions_, self.triangles_[t]);
      const double d = (c - q).squaredNorm();
      if (d < hit.squared || (d == hit.squared && t < hit.triangle)) {
        hit = Hit{t, c, d};
        const double b = std::sqrt(d) + self.reach_;
        bound2 = b * b;
      }
      return true;
    }
  };
  const double bound = std::sqrt(hit.squared) + reach_;
  Shrinking within{*this, q, hit, bound * bound};
  cover_tree_.findNeighbors(within, q.data(), nanoflann::SearchParams());
  return hit;
}

}  // namespace srcodec
