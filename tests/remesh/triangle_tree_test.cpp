#include "remesh/triangle_tree.h"

#include <gtest/gtest.h>

#include <random>
#include <thread>

#include "remesh/geometry.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

// Large, small and sliver triangles scattered in a box.
struct Soup {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int32_t, 3>> triangles;
};

Soup soup(int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto point = [&] { return Eigen::Vector3d(unit(random), unit(random), unit(random)); };
  Soup s;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d a = point();
    const double size = i % 3 == 0 ? 0.5 : 0.03;
    Eigen::Vector3d b = a + size * (point() - Eigen::Vector3d::Constant(0.5));
    Eigen::Vector3d c = a + size * (point() - Eigen::Vector3d::Constant(0.5));
    if (i % 5 == 0) {  // a sliver
      b = a + Eigen::Vector3d(0.6, 0.1, 0.05);
      c = a + 0.5 * (b - a) + 1e-3 * (point() - Eigen::Vector3d::Constant(0.5));
    }
    const auto first = static_cast<int32_t>(s.positions.size());
    s.positions.insert(s.positions.end(), {a, b, c});
    s.triangles.push_back({first, first + 1, first + 2});
  }
  return s;
}

// The nearest of all by checking every triangle (ties to the lower index).
TriangleTree::Hit brute_force(const Soup& s, const Eigen::Vector3d& q) {
  TriangleTree::Hit best;
  for (size_t t = 0; t < s.triangles.size(); ++t) {
    const auto& tri = s.triangles[t];
    Eigen::Vector3d c;
    const double d = squared_distance_to_triangle(q, s.positions[tri[0]], s.positions[tri[1]], s.positions[tri[2]], c);
    if (d < best.squared) best = {static_cast<int32_t>(t), c, d};
  }
  return best;
}

TEST(TriangleTree, FindsTheNearestOfAll) {
  const Soup s = soup(700, 7);
  const TriangleTree tree(s.positions, s.triangles);
  EXPECT_EQ(tree.size(), s.triangles.size());
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-0.3, 1.3);
  for (int i = 0; i < 4000; ++i) {
    const Eigen::Vector3d q(unit(random), unit(random), unit(random));
    const TriangleTree::Hit expected = brute_force(s, q);
    const TriangleTree::Hit hit = tree.closest(q);
    ASSERT_EQ(hit.squared, expected.squared) << "query " << i;
    EXPECT_NEAR((hit.point - q).squaredNorm(), hit.squared, 1e-12);
  }
}

TEST(TriangleTree, OnlyTheListedFaces) {
  const Soup s = soup(200, 3);
  std::vector<uint32_t> odd;
  for (uint32_t f = 1; f < s.triangles.size(); f += 2) odd.push_back(f);
  const TriangleTree tree(s.positions, s.triangles, odd);
  EXPECT_EQ(tree.size(), odd.size());
  Soup only;
  only.positions = s.positions;
  for (uint32_t f : odd) only.triangles.push_back(s.triangles[f]);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d q(unit(random), unit(random), unit(random));
    const TriangleTree::Hit hit = tree.closest(q);
    const TriangleTree::Hit expected = brute_force(only, q);
    ASSERT_EQ(hit.squared, expected.squared);
    EXPECT_EQ(hit.triangle, static_cast<int32_t>(odd[static_cast<size_t>(expected.triangle)]));
  }
}

TEST(TriangleTree, PointsOnTheSurfaceAreAtDistanceZero) {
  const TriangleMesh sphere = test::icosphere(3, 1.0);
  const TriangleTree tree(sphere.positions, sphere.triangles);
  for (size_t v = 0; v < sphere.positions.size(); ++v) EXPECT_EQ(tree.closest(sphere.positions[v]).squared, 0.0);
  const TriangleTree::Hit outside = tree.closest(Eigen::Vector3d(0, 0, 3));
  EXPECT_NEAR(std::sqrt(outside.squared), 2.0, 1e-9);  // a vertex of the icosphere is on the z axis
}

TEST(TriangleTree, PointsOnAFlatSquareAreExactlyOnIt) {
  const TriangleMesh square = test::flat_square(4);
  const TriangleTree tree(square.positions, square.triangles);
  std::mt19937 random(4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d q(unit(random), unit(random), 0.0);
    ASSERT_EQ(tree.closest(q).squared, 0.0);
    ASSERT_EQ(tree.closest(q + Eigen::Vector3d(0, 0, 0.25)).squared, 0.0625);
  }
}

TEST(TriangleTree, ConcurrentQueriesAgree) {
  const Soup s = soup(500, 9);
  const TriangleTree tree(s.positions, s.triangles);
  std::vector<Eigen::Vector3d> queries;
  std::mt19937 random(2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 2000; ++i) queries.emplace_back(unit(random), unit(random), unit(random));
  std::vector<double> alone(queries.size()), threaded(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) alone[i] = tree.closest(queries[i]).squared;
  std::vector<std::thread> threads;
  for (size_t t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (size_t i = t; i < queries.size(); i += 4) threaded[i] = tree.closest(queries[i]).squared;
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(alone, threaded);
}

TEST(TriangleTree, EmptyTreeFindsNothing) {
  const TriangleTree tree({}, {});
  EXPECT_EQ(tree.size(), 0u);
  EXPECT_EQ(tree.closest(Eigen::Vector3d::Zero()).triangle, -1);
}

}  // namespace
}  // namespace srcodec
