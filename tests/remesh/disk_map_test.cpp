#include "remesh/disk_map.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;

// A regular triangular lattice of n x n cells, counter-clockwise triangles:
// every inside vertex is the mean of its six neighbours.
struct Lattice {
  int n;
  std::vector<Eigen::Vector2d> uv;
  Triangles triangles;
  int32_t at(int i, int j) const { return j * (n + 1) + i; }
  bool on_boundary(int32_t v) const {
    const int i = v % (n + 1), j = v / (n + 1);
    return i == 0 || j == 0 || i == n || j == n;
  }
};

Lattice lattice(int n) {
  Lattice l{n, {}, {}};
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) l.uv.emplace_back(i + 0.5 * j, j * std::sqrt(3.0) / 2.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      l.triangles.push_back({l.at(i, j), l.at(i + 1, j), l.at(i, j + 1)});
      l.triangles.push_back({l.at(i + 1, j), l.at(i + 1, j + 1), l.at(i, j + 1)});
    }
  return l;
}

size_t flipped(const std::vector<Eigen::Vector2d>& uv, const Triangles& triangles) {
  size_t out = 0;
  for (const auto& t : triangles) out += !(signed_area2(uv[t[0]], uv[t[1]], uv[t[2]]) > 0.0);
  return out;
}

TEST(DiskMap, BoundaryLoopOfALatticeRunsAroundItCounterClockwise) {
  const Lattice l = lattice(4);
  const std::vector<int32_t> loop = disk_boundary_loop(l.uv.size(), l.triangles);
  ASSERT_EQ(loop.size(), 16u);
  std::set<int32_t> seen(loop.begin(), loop.end());
  EXPECT_EQ(seen.size(), loop.size());
  double area = 0.0;
  for (size_t j = 0; j < loop.size(); ++j) {
    EXPECT_TRUE(l.on_boundary(loop[j])) << loop[j];
    area += signed_area2(Eigen::Vector2d::Zero(), l.uv[loop[j]], l.uv[loop[(j + 1) % loop.size()]]);
  }
  EXPECT_GT(area, 0.0);
}

TEST(DiskMap, BoundaryLoopRefusesWhatIsNotOneDisk) {
  const Lattice l = lattice(4);
  // A hole: the six triangles around an inside vertex left out.
  Triangles annulus;
  const int32_t centre = l.at(2, 2);
  for (const auto& t : l.triangles)
    if (std::find(t.begin(), t.end(), centre) == t.end()) annulus.push_back(t);
  EXPECT_TRUE(disk_boundary_loop(l.uv.size(), annulus).empty());
  // Two triangles that share one corner only (pinched).
  EXPECT_TRUE(disk_boundary_loop(5, {{0, 1, 2}, {0, 3, 4}}).empty());
  // Two separate triangles.
  EXPECT_TRUE(disk_boundary_loop(6, {{0, 1, 2}, {3, 4, 5}}).empty());
  // A closed surface (a tetrahedron) has no boundary.
  EXPECT_TRUE(disk_boundary_loop(4, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}).empty());
  // An edge in three triangles.
  EXPECT_TRUE(disk_boundary_loop(5, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}).empty());
  // Neighbours that disagree on orientation.
  EXPECT_TRUE(disk_boundary_loop(4, {{0, 1, 2}, {0, 1, 3}}).empty());
  // Indices out of range, or a repeated corner.
  EXPECT_TRUE(disk_boundary_loop(3, {{0, 1, 3}}).empty());
  EXPECT_TRUE(disk_boundary_loop(3, {{0, 1, 1}}).empty());
  // One triangle is a disk.
  EXPECT_EQ(disk_boundary_loop(3, {{0, 1, 2}}).size(), 3u);
}

TEST(DiskMap, ConvexCombinationsReproduceARegularLattice) {
  const Lattice l = lattice(6);
  std::vector<char> fixed(l.uv.size(), 0);
  std::vector<Eigen::Vector2d> uv(l.uv.size(), Eigen::Vector2d(100.0, -100.0));
  std::vector<Eigen::Vector3d> positions(l.uv.size());
  for (size_t v = 0; v < l.uv.size(); ++v) {
    positions[v] = Eigen::Vector3d(l.uv[v].x(), l.uv[v].y(), 0.0);
    if (l.on_boundary(static_cast<int32_t>(v))) {
      fixed[v] = 1;
      uv[v] = l.uv[v];
    }
  }
  const std::vector<Eigen::Vector3d>* no_weights = nullptr;
  const std::vector<Eigen::Vector3d>* with_weights = &positions;
  for (const std::vector<Eigen::Vector3d>* weights : {no_weights, with_weights}) {
    std::vector<Eigen::Vector2d> out = uv;
    ASSERT_TRUE(convex_combination_map(l.uv.size(), l.triangles, weights, fixed, out));
    for (size_t v = 0; v < l.uv.size(); ++v) EXPECT_NEAR((out[v] - l.uv[v]).norm(), 0.0, 1e-9) << v;
  }
}

TEST(DiskMap, ConvexCombinationsOfADiskOnACircleFlipNothing) {
  // A lattice bent in 3D (weights from the bent lengths), its boundary on
  // the unit circle: Tutte's theorem says no triangle flips.
  const Lattice l = lattice(8);
  std::vector<Eigen::Vector3d> bent(l.uv.size());
  for (size_t v = 0; v < l.uv.size(); ++v)
    bent[v] = Eigen::Vector3d(l.uv[v].x(), l.uv[v].y(), std::sin(l.uv[v].x()) * 3.0);
  const std::vector<int32_t> loop = disk_boundary_loop(l.uv.size(), l.triangles);
  std::vector<char> fixed(l.uv.size(), 0);
  std::vector<Eigen::Vector2d> uv(l.uv.size(), Eigen::Vector2d::Zero());
  for (size_t j = 0; j < loop.size(); ++j) {
    const double angle = 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(loop.size());
    uv[loop[j]] = Eigen::Vector2d(std::cos(angle), std::sin(angle));
    fixed[loop[j]] = 1;
  }
  ASSERT_TRUE(convex_combination_map(l.uv.size(), l.triangles, &bent, fixed, uv));
  EXPECT_EQ(flipped(uv, l.triangles), 0u);
}

TEST(DiskMap, ConvexCombinationsNeedAFixedVertexInEachPart) {
  std::vector<Eigen::Vector2d> uv(6, Eigen::Vector2d::Zero());
  EXPECT_FALSE(convex_combination_map(6, {{0, 1, 2}, {3, 4, 5}}, nullptr, {1, 1, 1, 0, 0, 0}, uv));
  uv.assign(6, Eigen::Vector2d::Ones());
  EXPECT_TRUE(convex_combination_map(6, {{0, 1, 2}, {3, 4, 5}}, nullptr, {1, 1, 1, 1, 1, 1}, uv));
}

TEST(DiskMap, UntanglingUndoesFlipsInsideAFixedRim) {
  const Lattice l = lattice(5);
  std::vector<char> fixed(l.uv.size(), 0);
  for (size_t v = 0; v < l.uv.size(); ++v) fixed[v] = l.on_boundary(static_cast<int32_t>(v));
  std::vector<Eigen::Vector2d> uv = l.uv;
  // Two inside vertices swapped, a third thrown past the rim.
  std::swap(uv[l.at(2, 2)], uv[l.at(3, 2)]);
  uv[l.at(1, 3)] = Eigen::Vector2d(-4.0, 9.0);
  ASSERT_GT(flipped(uv, l.triangles), 0u);
  EXPECT_EQ(untangle_planar(l.uv.size(), l.triangles, fixed, uv, 64), 0u);
  EXPECT_EQ(flipped(uv, l.triangles), 0u);
  for (size_t v = 0; v < l.uv.size(); ++v)
    if (fixed[v]) {
      EXPECT_EQ(uv[v], l.uv[v]) << "a fixed vertex moved: " << v;
    }
}

TEST(DiskMap, UntanglingLeavesAnUnflippedMapAlone) {
  const Lattice l = lattice(3);
  std::vector<char> fixed(l.uv.size(), 0);
  std::vector<Eigen::Vector2d> uv = l.uv;
  EXPECT_EQ(untangle_planar(l.uv.size(), l.triangles, fixed, uv, 8), 0u);
  EXPECT_EQ(uv, l.uv);
}

TEST(DiskMap, LocatorFindsTheTriangleAndBarycentrics) {
  const Lattice l = lattice(7);
  const PlanarLocator locator(l.uv, l.triangles);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    // A random point of a random triangle.
    const auto& t = l.triangles[rng() % l.triangles.size()];
    double a = unit(rng), b = unit(rng);
    if (a + b > 1.0) {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    const Eigen::Vector2d p = (1.0 - a - b) * l.uv[t[0]] + a * l.uv[t[1]] + b * l.uv[t[2]];
    Eigen::Vector3d w;
    const int32_t found = locator.locate(p, &w);
    ASSERT_GE(found, 0);
    EXPECT_GE(w.minCoeff(), -1e-12);
    const auto& f = l.triangles[found];
    EXPECT_NEAR((w[0] * l.uv[f[0]] + w[1] * l.uv[f[1]] + w[2] * l.uv[f[2]] - p).norm(), 0.0, 1e-9);
    EXPECT_NEAR(w.sum(), 1.0, 1e-12);
  }
  // Outside: the nearest cell's triangle, with a negative coordinate.
  Eigen::Vector3d w;
  ASSERT_GE(locator.locate(Eigen::Vector2d(-3.0, -3.0), &w), 0);
  EXPECT_LT(w.minCoeff(), 0.0);
  // No triangles: nothing to find.
  const std::vector<Eigen::Vector2d> none_uv;
  const Triangles none;
  EXPECT_EQ(PlanarLocator(none_uv, none).locate(Eigen::Vector2d::Zero(), &w), -1);
}

}  // namespace
}  // namespace srcodec
