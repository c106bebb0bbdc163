// Sharp features (remesh/features.h) on shapes whose features are known: a
// cube's edges and corners, a smooth sphere and a noisy one (none), a square
// sheet's boundary, a folded sheet whose crease runs into its boundary, and
// a ridge that fades out (a crease with an end inside the surface).
#include "remesh/features.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "remesh/adjacency.h"
#include "remesh/geometry.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

size_t count(const Features& f, FeatureKind kind) {
  size_t n = 0;
  for (const FeatureEdge& e : f.edges) n += e.kind == kind;
  return n;
}

using test::grid_cube;
using test::GridBuilder;

TEST(Features, CubeHasTwelveEdgesAndEightCorners) {
  const int n = 8;
  const TriangleMesh cube = grid_cube(n);
  ASSERT_EQ(cube.positions.size(), 6u * n * n + 2);
  const Features f = detect_features(cube);
  EXPECT_EQ(count(f, FeatureKind::kCrease), 12u * n);
  EXPECT_EQ(count(f, FeatureKind::kBoundary), 0u);
  ASSERT_EQ(f.corners.size(), 8u);
  for (int32_t c : f.corners) EXPECT_NEAR(cube.positions[c].cwiseAbs().minCoeff(), 1.0, 1e-12);
  EXPECT_TRUE(f.ends.empty());
  ASSERT_EQ(f.curves.size(), 12u);
  for (const FeatureCurve& c : f.curves) {
    EXPECT_EQ(c.vertices.size(), static_cast<size_t>(n) + 1);
    EXPECT_FALSE(c.closed());
  }
  // Face diagonals and grid lines inside a face are not features.
  EXPECT_TRUE(f.is_feature(f.curves[0].vertices[0], f.curves[0].vertices[1]));
  EXPECT_TRUE(f.is_feature(f.curves[0].vertices[1], f.curves[0].vertices[0]));
  for (const auto& t : cube.triangles) {
    const Eigen::Vector3d centroid = (cube.positions[t[0]] + cube.positions[t[1]] + cube.positions[t[2]]) / 3.0;
    if ((centroid.cwiseAbs().array() > 0.5).count() == 1) {  // away from the cube's edges
      for (int c = 0; c < 3; ++c) EXPECT_FALSE(f.is_feature(t[c], t[(c + 1) % 3]));
    }
  }
}

TEST(Features, CubeOfTwelveTrianglesIsAllCorners) {
  const TriangleMesh cube = test::unit_cube();
  const Features f = detect_features(cube);
  EXPECT_EQ(count(f, FeatureKind::kCrease), 12u);
  EXPECT_EQ(f.corners.size(), 8u);
  EXPECT_EQ(f.curves.size(), 12u);
  for (const FeatureCurve& c : f.curves) EXPECT_EQ(c.vertices.size(), 2u);
}

TEST(Features, SmoothAndNoisySpheresHaveNone) {
  const TriangleMesh sphere = test::icosphere(4, 1.0);
  EXPECT_TRUE(detect_features(sphere).edges.empty());
  // Noise of a third of an edge length: many single edges bend past 30
  // degrees, but none stands out of the noise around it for long.
  TriangleMesh noisy = sphere;
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 0.33 * 0.06);  // icosphere(4) edges are about 0.06 long
  for (auto& p : noisy.positions) p += Eigen::Vector3d(noise(random), noise(random), noise(random));
  const auto across = triangles_across(noisy.triangles);
  size_t sharp_single = 0;
  for (size_t f = 0; f < noisy.triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int32_t g = across[f][c];
      if (g > static_cast<int32_t>(f) && degrees_between(triangle_normal(noisy.positions, noisy.triangles[f]),
                                                         triangle_normal(noisy.positions, noisy.triangles[g])) > 30.0)
        ++sharp_single;
    }
  EXPECT_GT(sharp_single, 100u) << "the noise bends many single edges";
  const Features f = detect_features(noisy);
  EXPECT_TRUE(f.edges.empty()) << f.edges.size() << " crease edges";
}

TEST(Features, SquareSheetHasItsBoundaryAndFourCorners) {
  GridBuilder g;
  const int n = 10;
  g.patch(n, [](double u, double v) { return Eigen::Vector3d(u, v, 0); });
  const Features f = detect_features(g.mesh);
  EXPECT_EQ(count(f, FeatureKind::kBoundary), 4u * n);
  EXPECT_EQ(count(f, FeatureKind::kCrease), 0u);
  ASSERT_EQ(f.corners.size(), 4u);
  for (int32_t c : f.corners) {
    const Eigen::Vector3d& p = g.mesh.positions[c];
    EXPECT_TRUE((p.x() == 0 || p.x() == 1) && (p.y() == 0 || p.y() == 1)) << p.transpose();
  }
  EXPECT_EQ(f.curves.size(), 4u);
  FeatureOptions no_boundaries;
  no_boundaries.boundaries = false;
  EXPECT_TRUE(detect_features(g.mesh, no_boundaries).edges.empty());
}

TEST(Features, CreaseRunningIntoTheBoundary) {
  // Two unit squares folded at 90 degrees along x = 0: the crease meets the
  // boundary at both its ends, where three feature edges meet.
  GridBuilder g;
  const int n = 12;
  g.patch(n, [](double u, double v) { return Eigen::Vector3d(-u, v, 0); });
  g.patch(n, [](double u, double v) { return Eigen::Vector3d(0, u, v); });
  const Features f = detect_features(g.mesh);
  EXPECT_EQ(count(f, FeatureKind::kCrease), static_cast<size_t>(n));
  size_t crease_ends_on_boundary = 0;
  for (int32_t c : f.corners) {
    const Eigen::Vector3d& p = g.mesh.positions[c];
    if (p.x() == 0 && p.z() == 0 && (p.y() == 0 || p.y() == 1)) ++crease_ends_on_boundary;
  }
  EXPECT_EQ(crease_ends_on_boundary, 2u);
  EXPECT_TRUE(f.ends.empty());
}

TEST(Features, RidgeThatFadesOutEndsInsideTheSurface) {
  // z = -2 (1 - x) |y| over [0, 1] x [-1, 1]: a ridge along y = 0 whose two
  // sides meet at 2 atan(2 (1 - x)), over 30 degrees up to x = 0.87, then
  // flatter and flatter.
  GridBuilder g;
  const int n = 24;
  g.patch(n, [](double u, double v) {
    const double x = u, y = 2 * v - 1;
    return Eigen::Vector3d(x, y, -2 * (1 - x) * std::abs(y));
  });
  const Features f = detect_features(g.mesh);
  ASSERT_GT(count(f, FeatureKind::kCrease), 0u);
  for (const FeatureEdge& e : f.edges)
    if (e.kind == FeatureKind::kCrease) {
      EXPECT_EQ(g.mesh.positions[e.a].y(), 0.0);
      EXPECT_EQ(g.mesh.positions[e.b].y(), 0.0);
    }
  ASSERT_EQ(f.ends.size(), 1u);
  const double end = g.mesh.positions[f.ends[0]].x();
  // Within a radius (4 median edges, 0.33 here) of the ridge's end the walk
  // goes round it, so the crease stops up to a radius short of 0.87.
  EXPECT_GE(end, 0.87 - 0.34 - 1.0 / n);
  EXPECT_LE(end, 0.875);
}

}  // namespace
}  // namespace srcodec
