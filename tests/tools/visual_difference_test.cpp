// The visual measure (tools/measure/visual_difference.h) on cases whose
// answers are known: a mesh against itself, a sphere with some triangles
// turned over, and a cube against the same cube with bevelled edges and
// corners, whose figures follow from the faces' projected areas.
#include "tools/measure/visual_difference.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "remesh/geometry.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

constexpr double kPi = 3.14159265358979323846;

VisualDifference measured(const TriangleMesh& reference, const TriangleMesh& test, const VisualOptions& o = {}) {
  const StatusOr<VisualDifference> d = visual_difference(reference, test, o);
  EXPECT_TRUE(d.ok()) << d.status().message();
  return d.ok() ? *d : VisualDifference{};
}

TEST(VisualDifference, MeshAgainstItselfShowsNothing) {
  const TriangleMesh sphere = test::icosphere(4, 1.5);
  const VisualDifference d = measured(sphere, sphere);
  // Each view frames the bounding box's half diagonal, r sqrt(3): the sphere
  // covers pi / 12 of it.
  EXPECT_NEAR(static_cast<double>(d.pixels), 16 * 256 * 256 * kPi / 12, 0.01 * 16 * 256 * 256 * kPi / 12);
  EXPECT_EQ(d.mean_normal_degrees, 0.0);
  EXPECT_EQ(d.defect_share, 0.0);
  EXPECT_TRUE(std::isinf(d.depth_psnr) && d.depth_psnr > 0);
  EXPECT_EQ(d.turned_over_share, 0.0);
}

TEST(VisualDifference, TurnedOverTrianglesAreCountedAndSeen) {
  const TriangleMesh sphere = test::icosphere(4, 1.0);
  TriangleMesh flipped = sphere;
  double flipped_area = 0, total_area = 0;
  for (size_t f = 0; f < flipped.triangles.size(); ++f) {
    total_area += triangle_area(sphere.positions, sphere.triangles[f]);
    if (f % 7 != 3) continue;
    std::swap(flipped.triangles[f][1], flipped.triangles[f][2]);
    flipped_area += triangle_area(sphere.positions, sphere.triangles[f]);
  }
  const VisualDifference d = measured(sphere, flipped);
  // Exact: each flipped triangle faces against itself, every other one along.
  EXPECT_NEAR(d.turned_over_share, flipped_area / total_area, 1e-12);
  // The same surface: every pixel shows 0 or 180 degrees, so the mean angle
  // is 180 times the defect share (both over the same pixels).
  EXPECT_NEAR(d.mean_normal_degrees, 180.0 * d.defect_share, 1e-6);
  // A scattered seventh of a sphere, seen from all round, covers about the
  // same share of the pixels as of the area.
  EXPECT_NEAR(d.defect_share, flipped_area / total_area, 0.02 * flipped_area / total_area);
  EXPECT_GT(d.depth_psnr, 120.0);  // the same points, up to Embree's rounding with the corners in another order
}

// The convex polytope with these vertices whose faces lie on the planes
// n . p = max over the vertices (n of unit length), each face fanned from
// its first vertex in counter-clockwise order seen from outside.
TriangleMesh convex_polytope(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Eigen::Vector3d>& normals,
                             std::vector<int>* face_of_triangle) {
  TriangleMesh m;
  m.positions = vertices;
  for (size_t k = 0; k < normals.size(); ++k) {
    const Eigen::Vector3d& n = normals[k];
    double top = -1e300;
    for (const auto& p : vertices) top = std::max(top, n.dot(p));
    std::vector<int32_t> on;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (size_t v = 0; v < vertices.size(); ++v)
      if (n.dot(vertices[v]) > top - 1e-9) {
        on.push_back(static_cast<int32_t>(v));
        centre += vertices[v];
      }
    centre /= static_cast<double>(on.size());
    const Eigen::Vector3d u = (vertices[on[0]] - centre).normalized(), w = n.cross(u);
    std::sort(on.begin(), on.end(), [&](int32_t a, int32_t b) {
      const Eigen::Vector3d da = vertices[a] - centre, db = vertices[b] - centre;
      return std::atan2(w.dot(da), u.dot(da)) < std::atan2(w.dot(db), u.dot(db));
    });
    for (size_t i = 1; i + 1 < on.size(); ++i) {
      m.triangles.push_back({on[0], on[i], on[i + 1]});
      if (face_of_triangle) face_of_triangle->push_back(static_cast<int>(k));
    }
  }
  return m;
}

TEST(VisualDifference, CubeAgainstBevelledCubeMatchesProjectedAreas) {
  // The cube [-1, 1]^3 and the same cube with every edge cut at 45 degrees
  // by b and every corner by a triangle.
  const double b = 0.3;
  std::vector<Eigen::Vector3d> cube_vertices, bevel_vertices, face_normals, bevel_normals;
  for (int i = 0; i < 8; ++i) cube_vertices.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {-1.0, 1.0}) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n[axis] = s;
      face_normals.push_back(n);
      for (double y : {-1.0, 1.0})
        for (double z : {-1.0, 1.0}) {
          Eigen::Vector3d p;
          p[axis] = s;
          p[(axis + 1) % 3] = y * (1 - b);
          p[(axis + 2) % 3] = z * (1 - b);
          bevel_vertices.push_back(p);
        }
    }
  bevel_normals = face_normals;
  const size_t strips_from = bevel_normals.size();
  for (int axis = 0; axis < 3; ++axis)  // the edges along `axis`
    for (double y : {-1.0, 1.0})
      for (double z : {-1.0, 1.0}) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        n[(axis + 1) % 3] = y;
        n[(axis + 2) % 3] = z;
        bevel_normals.push_back(n.normalized());
      }
  const size_t corners_from = bevel_normals.size();
  for (const auto& c : cube_vertices) bevel_normals.push_back(c.normalized());
  const TriangleMesh cube = convex_polytope(cube_vertices, face_normals, nullptr);
  std::vector<int> face_of;
  const TriangleMesh bevelled = convex_polytope(bevel_vertices, bevel_normals, &face_of);
  ASSERT_EQ(cube.triangles.size(), 12u);
  ASSERT_EQ(bevelled.triangles.size(), 6u * 2 + 12 * 2 + 8);

  // Projected areas seen from each view: the cube's outline (where one mesh
  // or both are seen), the bevelled cube's, and its bevels' (45 degrees from
  // the cube face behind them) and corners' (54.7 degrees).
  VisualOptions o;
  double outline = 0, inner = 0, defect_area = 0, angle_area = 0;
  const double corner_angle = std::acos(1.0 / std::sqrt(3.0)) * 180.0 / kPi;
  for (const Eigen::Vector3d& d : view_directions(o.views)) {
    for (const auto& t : cube.triangles) {
      outline += std::max(0.0, 0.5 * triangle_normal(cube.positions, t).dot(d));
    }
    for (size_t f = 0; f < bevelled.triangles.size(); ++f) {
      const auto& t = bevelled.triangles[f];
      const double a = std::max(0.0, 0.5 * triangle_normal(bevelled.positions, t).dot(d));
      inner += a;
      const size_t plane = static_cast<size_t>(face_of[f]);
      if (plane >= strips_from) defect_area += a;
      angle_area += a * (plane >= corners_from ? corner_angle : plane >= strips_from ? 45.0 : 0.0);
    }
  }
  const VisualDifference d = measured(cube, bevelled, o);
  // The bevels and corners, and the cube outside the bevelled one, are
  // defects; the faces are not.
  EXPECT_NEAR(d.defect_share, (defect_area + outline - inner) / outline, 0.005);
  EXPECT_NEAR(d.mean_normal_degrees, angle_area / inner, 0.3);
  EXPECT_EQ(d.turned_over_share, 0.0);
  EXPECT_TRUE(std::isfinite(d.depth_psnr));
  EXPECT_GT(d.depth_psnr, 20.0);
}

TEST(VisualDifference, SameFiguresOnOneThreadOrMoreAndFarFromTheOrigin) {
  TriangleMesh sphere = test::icosphere(3, 1.0);
  TriangleMesh bumpy = sphere;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-0.02, 0.02);
  for (auto& p : bumpy.positions) p += Eigen::Vector3d(unit(random), unit(random), unit(random));
  const VisualDifference many = measured(sphere, bumpy);
  VisualDifference one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = measured(sphere, bumpy);
  }
  EXPECT_EQ(one.mean_normal_degrees, many.mean_normal_degrees);
  EXPECT_EQ(one.defect_share, many.defect_share);
  EXPECT_EQ(one.depth_psnr, many.depth_psnr);
  EXPECT_EQ(one.turned_over_share, many.turned_over_share);
  EXPECT_GT(many.mean_normal_degrees, 0.5);
  // A scan's coordinates often sit far from the origin: the renders are made
  // about the reference's own centre, so the figures barely move.
  const Eigen::Vector3d far(2.5e6, -1.0e6, 3.0e5);
  for (auto& p : sphere.positions) p += far;
  for (auto& p : bumpy.positions) p += far;
  const VisualDifference moved = measured(sphere, bumpy);
  EXPECT_NEAR(moved.mean_normal_degrees, many.mean_normal_degrees, 1e-3 * many.mean_normal_degrees);
  EXPECT_NEAR(moved.defect_share, many.defect_share, 1e-3);
  EXPECT_NEAR(moved.depth_psnr, many.depth_psnr, 0.05);
}

TEST(VisualDifference, OneWildVertexDoesNotBlurTheRest) {
  // A decoded mesh with one vertex thrown a million radii away: its
  // triangles are defects, the rest still measures as before.
  const TriangleMesh sphere = test::icosphere(4, 1.0);
  TriangleMesh wild = sphere;
  wild.positions[0] = Eigen::Vector3d(1e6, 0, 0);
  const VisualDifference d = measured(sphere, wild);
  EXPECT_GT(d.defect_share, 0.0);
  EXPECT_LT(d.defect_share, 0.05);
  EXPECT_GT(d.depth_psnr, 120.0) << "the untouched surface keeps exact depths";
}

TEST(VisualDifference, RefusesBadOptionsAndBadMeshes) {
  const TriangleMesh sphere = test::icosphere(2, 1.0);
  VisualOptions o;
  o.views = 8;
  StatusOr<VisualDifference> d = visual_difference(sphere, sphere, o);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(d.status().message().find("views"), std::string::npos) << d.status().message();
  o = VisualOptions{};
  o.resolution = 5000;
  d = visual_difference(sphere, sphere, o);
  ASSERT_FALSE(d.ok());
  EXPECT_NE(d.status().message().find("resolution"), std::string::npos) << d.status().message();

  TriangleMesh broken = sphere;
  broken.triangles[4][1] = 100000;
  d = visual_difference(sphere, broken);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().code(), StatusCode::kInvalidMesh);
  EXPECT_NE(d.status().message().find("test mesh: triangle 4"), std::string::npos) << d.status().message();
}

}  // namespace
}  // namespace srcodec
