#include "remesh/nearest_triangle.h"

#include <gtest/gtest.h>

#include <random>

#include "remesh/geometry.h"

namespace srcodec {
namespace {

// The nearest triangle by measuring every one (ties to the lower index).
NearestTriangle::Hit nearest_of_all(const Eigen::Vector3d& q, const std::vector<Eigen::Vector3d>& positions,
                                    const std::vector<std::array<int32_t, 3>>& triangles) {
  NearestTriangle::Hit best;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const Eigen::Vector3d c = closest_on_triangle(q, positions[tri[0]], positions[tri[1]], positions[tri[2]]);
    const double d = (c - q).squaredNorm();
    if (d < best.squared) best = NearestTriangle::Hit{static_cast<int32_t>(t), c, d};
  }
  return best;
}

// A soup of large, small and sliver triangles: the triangles with the
// nearest centroids are often not the nearest, and exact() must still find
// the nearest of all (ties to the lower index), as a search of every
// triangle does, wherever its search starts.
TEST(NearestTriangle, ExactFindsTheNearestOfAll) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto point = [&] { return Eigen::Vector3d(unit(random), unit(random), unit(random)); };
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int32_t, 3>> triangles;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d a = point();
    const double size = i % 3 == 0 ? 0.5 : 0.03;
    Eigen::Vector3d b = a + size * (point() - Eigen::Vector3d::Constant(0.5));
    Eigen::Vector3d c = a + size * (point() - Eigen::Vector3d::Constant(0.5));
    if (i % 5 == 0) {  // a sliver: long and a thousandth as wide
      b = a + Eigen::Vector3d(0.6, 0.1, 0.05);
      c = a + 0.5 * (b - a) + 1e-3 * (point() - Eigen::Vector3d::Constant(0.5));
    }
    const int32_t first = static_cast<int32_t>(positions.size());
    positions.insert(positions.end(), {a, b, c});
    triangles.push_back({first, first + 1, first + 2});
  }
  const NearestTriangle nearest(positions, triangles, /*exact_search=*/true);
  size_t missed_by_centroids = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d q = 1.4 * point() - Eigen::Vector3d::Constant(0.2);
    const NearestTriangle::Hit best = nearest_of_all(q, positions, triangles);
    // From the nearest centroids, and from a given triangle (any: the
    // answer must not depend on it).
    for (const int32_t start : {-1, static_cast<int32_t>(random() % triangles.size()), best.triangle}) {
      const NearestTriangle::Hit hit = nearest.exact(q, start);
      ASSERT_EQ(hit.triangle, best.triangle) << "query " << i << " from " << start;
      EXPECT_EQ(hit.squared, best.squared) << "query " << i << " from " << start;
    }
    missed_by_centroids += nearest(q).triangle != best.triangle;
  }
  EXPECT_GT(missed_by_centroids, 30u);  // the soup does test the exact search
}

// A fine grid with a few triangles a hundred of its edges long across it,
// as a damaged scan has: those are not covered but measured one by one, and
// exact() still finds the nearest of all.
TEST(NearestTriangle, ExactWithAFewVeryLongTriangles) {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int32_t, 3>> triangles;
  constexpr int kGrid = 100;  // edge 0.01
  for (int j = 0; j <= kGrid; ++j)
    for (int i = 0; i <= kGrid; ++i) positions.emplace_back(0.01 * i, 0.01 * j, 0.0);
  for (int j = 0; j < kGrid; ++j)
    for (int i = 0; i < kGrid; ++i) {
      const int32_t a = j * (kGrid + 1) + i, b = a + 1, c = a + kGrid + 1, d = c + 1;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
  const size_t long_first = triangles.size();
  for (const double z : {0.05, 0.2, -0.1}) {
    const int32_t first = static_cast<int32_t>(positions.size());
    positions.insert(positions.end(), {{0.0, 0.1, z}, {1.0, 0.9, z + 0.3}, {0.5, 0.52, z + 0.002}});
    triangles.push_back({first, first + 1, first + 2});
  }
  const NearestTriangle nearest(positions, triangles, /*exact_search=*/true);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-0.2, 1.2);
  size_t on_long = 0;
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d q(unit(random), unit(random), 0.3 * unit(random));
    const NearestTriangle::Hit best = nearest_of_all(q, positions, triangles);
    for (const int32_t start : {-1, static_cast<int32_t>(random() % triangles.size())}) {
      const NearestTriangle::Hit hit = nearest.exact(q, start);
      ASSERT_EQ(hit.triangle, best.triangle) << "query " << i << " from " << start;
      EXPECT_EQ(hit.squared, best.squared) << "query " << i << " from " << start;
    }
    on_long += static_cast<size_t>(best.triangle) >= long_first;
  }
  EXPECT_GT(on_long, 100u);  // the long triangles are often the answer
}

}  // namespace
}  // namespace srcodec
