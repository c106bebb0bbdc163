#include "format/crease_normals.h"

#include <gtest/gtest.h>

#include <map>

#include "tests/test_util.h"

namespace srcodec {
namespace {

using Edge = std::array<int32_t, 2>;

Eigen::Vector3d face_normal(const TriangleMesh& m, const std::array<int32_t, 3>& t) {
  return (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
}

// The usual smooth normals: per vertex, the area-weighted average of its
// triangles' normals.
std::vector<Eigen::Vector3d> vertex_normals(const TriangleMesh& m) {
  std::vector<Eigen::Vector3d> sum(m.positions.size(), Eigen::Vector3d::Zero());
  for (const auto& t : m.triangles)
    for (int32_t v : t) sum[v] += face_normal(m, t);
  for (auto& n : sum) n.normalize();
  return sum;
}

// The edges whose two triangles face different ways: on a cube, its 12
// edges (split where the grid splits them), not the faces' diagonals.
std::vector<Edge> folded_edges(const TriangleMesh& m) {
  std::map<Edge, std::vector<Eigen::Vector3d>> normals;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      normals[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}].push_back(
          face_normal(m, t).normalized());
  std::vector<Edge> out;
  for (const auto& [edge, n] : normals)
    if (n.size() == 2 && n[0].dot(n[1]) < 0.5) out.push_back(edge);
  return out;
}

void expect_consistent(const TriangleMesh& m, const SectorNormals& s) {
  ASSERT_EQ(s.corners.size(), m.triangles.size());
  ASSERT_EQ(s.vertex.size(), s.normals.size());
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(s.corners[t][k], 0);
      ASSERT_LT(static_cast<size_t>(s.corners[t][k]), s.normals.size());
      EXPECT_EQ(s.vertex[s.corners[t][k]], m.triangles[t][k]) << t << " " << k;
    }
  EXPECT_TRUE(std::is_sorted(s.vertex.begin(), s.vertex.end()));
}

// A cube with its 12 edges creased: every corner's normal is its face's,
// exactly; a vertex inside a face has one sector, one inside a cube edge two,
// a cube corner three.
TEST(CreaseNormals, ACubeCreasedOnItsEdgesHasFaceNormalsAtEveryCorner) {
  TriangleMesh cube = test::grid_cube(4);
  const std::vector<Edge> creases = folded_edges(cube);
  ASSERT_EQ(creases.size(), 12u * 4);
  cube.positions.emplace_back(5, 5, 5);  // used by no triangle: one sector, no normal
  const SectorNormals s = crease_normals(cube, creases);
  expect_consistent(cube, s);
  for (size_t t = 0; t < cube.triangles.size(); ++t) {
    const Eigen::Vector3f face = face_normal(cube, cube.triangles[t]).normalized().cast<float>();
    for (int k = 0; k < 3; ++k) EXPECT_EQ(s.normals[s.corners[t][k]], face) << t << " " << k;
  }
  std::map<int, int> sectors_by_ones;  // how many coordinates are +-1 -> sectors
  for (size_t v = 0; v + 1 < cube.positions.size(); ++v) {
    const int ones = (cube.positions[v].array().abs() == 1.0).count();
    const auto n = std::count(s.vertex.begin(), s.vertex.end(), static_cast<int32_t>(v));
    EXPECT_EQ(n, ones) << v;
  }
  EXPECT_EQ(s.vertex.back(), static_cast<int32_t>(cube.positions.size() - 1));
  EXPECT_EQ(s.normals.back(), Eigen::Vector3f::Zero());
  EXPECT_EQ(s.normals.size(), 6u * 9 + 12u * 3 * 2 + 8u * 3 + 1);
}

// Creased only around its top face: the top face's corners get (0, 0, 1);
// on the other side of the crease, the sides' sector, which has no z.
TEST(CreaseNormals, ACreaseLoopSplitsItsVerticesInTwo) {
  const TriangleMesh cube = test::grid_cube(2);
  std::vector<Edge> top;
  for (const Edge& e : folded_edges(cube))
    if (cube.positions[e[0]].z() == 1 && cube.positions[e[1]].z() == 1) top.push_back(e);
  ASSERT_EQ(top.size(), 8u);
  const SectorNormals s = crease_normals(cube, top);
  expect_consistent(cube, s);
  const std::vector<Eigen::Vector3d> smooth = vertex_normals(cube);
  for (size_t t = 0; t < cube.triangles.size(); ++t) {
    const bool on_top = face_normal(cube, cube.triangles[t]).z() > 0;
    for (int k = 0; k < 3; ++k) {
      const int32_t v = cube.triangles[t][k];
      const Eigen::Vector3f n = s.normals[s.corners[t][k]];
      if (cube.positions[v].z() < 1) {
        EXPECT_LT((n.cast<double>() - smooth[v]).norm(), 1e-6) << v;  // off the crease: smooth
      } else if (on_top) {
        EXPECT_EQ(n, Eigen::Vector3f(0, 0, 1)) << v;
      } else {
        EXPECT_EQ(n.z(), 0.0f) << v;
        EXPECT_NEAR(n.norm(), 1.0f, 1e-6f) << v;
      }
    }
  }
  EXPECT_EQ(s.normals.size(), cube.positions.size() + 8);
}

// A smooth sphere: one sector per vertex, numbered as the vertices, with the
// usual vertex normals; a crease edge that ends at a vertex (a dart) leaves
// both its ends one sector, and pairs that are no edge of the mesh change
// nothing.
TEST(CreaseNormals, ASmoothSphereAndADartHaveTheUsualVertexNormals) {
  const TriangleMesh sphere = test::icosphere(3, 1.0);
  const std::vector<Eigen::Vector3d> smooth = vertex_normals(sphere);
  const SectorNormals plain = crease_normals(sphere, {});
  expect_consistent(sphere, plain);
  ASSERT_EQ(plain.normals.size(), sphere.positions.size());
  EXPECT_EQ(plain.corners, sphere.triangles);
  for (size_t v = 0; v < smooth.size(); ++v) {
    EXPECT_LT((plain.normals[v].cast<double>() - smooth[v]).norm(), 1e-6) << v;
    EXPECT_LT((plain.normals[v].cast<double>() - sphere.positions[v]).norm(), 0.01) << v;
  }
  const auto& t = sphere.triangles[7];
  const Edge dart{std::min(t[0], t[1]), std::max(t[0], t[1])};
  for (const std::vector<Edge>& creases : {std::vector<Edge>{dart}, std::vector<Edge>{{t[1], t[0]}},
                                           std::vector<Edge>{{0, 400}, {3, 3}}}) {
    const SectorNormals s = crease_normals(sphere, creases);
    EXPECT_EQ(s.corners, plain.corners);
    EXPECT_EQ(s.normals, plain.normals);
  }
}

// A crease through a vertex (two crease edges at it) splits it in two, and
// each side's normal averages that side's triangles only.
TEST(CreaseNormals, ACreaseThroughAVertexSplitsItsFan) {
  const TriangleMesh sphere = test::icosphere(2, 1.0);
  // Vertex 0 and two of its neighbours that are not neighbours of each other.
  std::vector<int32_t> ring;
  for (const auto& t : sphere.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] == 0) ring.push_back(t[(k + 1) % 3]);
  ASSERT_EQ(ring.size(), 5u);
  const int32_t a = ring[0];
  int32_t b = -1;
  for (const auto& t : sphere.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] == 0 && t[(k + 1) % 3] != a && t[(k + 2) % 3] != a && b < 0) b = t[(k + 2) % 3];
  ASSERT_GE(b, 0);
  const SectorNormals s = crease_normals(sphere, {{0, a}, {0, b}});
  expect_consistent(sphere, s);
  EXPECT_EQ(s.normals.size(), sphere.positions.size() + 1);
  EXPECT_EQ(s.vertex[0], 0);
  EXPECT_EQ(s.vertex[1], 0);
  Eigen::Vector3d side[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (size_t t = 0; t < sphere.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (sphere.triangles[t][k] == 0) side[s.corners[t][k]] += face_normal(sphere, sphere.triangles[t]);
  for (int i = 0; i < 2; ++i) EXPECT_LT((s.normals[i].cast<double>() - side[i].normalized()).norm(), 1e-6);
  EXPECT_GT((s.normals[0] - s.normals[1]).norm(), 0.05f);
}

}  // namespace
}  // namespace srcodec
