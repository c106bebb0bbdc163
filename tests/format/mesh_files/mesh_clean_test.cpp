#include "format/mesh_files/mesh_clean.h"

#include <gtest/gtest.h>

#include <set>

#include "format/mesh_files/mesh_io.h"
#include "format/mesh_files/mesh_stats.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

PolygonMesh soup(std::vector<Eigen::Vector3d> positions, const std::vector<std::vector<int32_t>>& faces) {
  PolygonMesh m;
  m.positions = std::move(positions);
  for (const auto& f : faces) m.add_face(f.data(), static_cast<int32_t>(f.size()));
  return m;
}

TEST(MeshClean, WeldsCoincidentVerticesAndDropsUnreferenced) {
  // Two triangles of a square written with separate corners, plus a stray vertex.
  PolygonMesh m = soup({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {5, 5, 5}},
                       {{0, 1, 2}, {3, 4, 5}});
  CleanReport r;
  TriangleMesh out = clean_mesh(m, &r);
  EXPECT_EQ(r.welded_vertices, 2u);
  EXPECT_EQ(r.unreferenced_vertices, 1u);
  ASSERT_EQ(out.positions.size(), 4u);
  ASSERT_EQ(out.triangles.size(), 2u);
  EXPECT_EQ(compute_stats(to_polygon_mesh(out)).boundary_loops, 1u);
  EXPECT_EQ(compute_stats(to_polygon_mesh(out)).edges, 5u);
}

TEST(MeshClean, DropsDegenerateAndDuplicateFaces) {
  PolygonMesh m = soup({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}},
                       {{0, 1, 2}, {2, 1, 0}, {0, 1, 1}, {0, 1, 3}});
  CleanReport r;
  TriangleMesh out = clean_mesh(m, &r);
  EXPECT_EQ(r.duplicate_faces, 1u);   // {2,1,0} repeats {0,1,2} flipped
  EXPECT_EQ(r.degenerate_faces, 2u);  // repeated corner; collinear corners
  ASSERT_EQ(out.triangles.size(), 1u);
  EXPECT_EQ(out.triangles[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(r.unreferenced_vertices, 1u);
}

// A zero-area triangle whose corners are distinct (m on the segment p-q)
// between three others: dropped alone it leaves a hole of no width, two
// boundary loops. The triangle across p-q is split at m instead, and the
// diamond stays one disk.
TEST(MeshClean, ClosesTheHoleOfAZeroAreaTriangle) {
  //          c
  //   a -----m----- b     (a, b, m) has no area
  //          d
  PolygonMesh m = soup({{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {1, 1, 0}, {1, -1, 0}},
                       {{0, 1, 3}, {1, 0, 2}, {0, 4, 2}, {2, 4, 1}});
  CleanReport r;
  TriangleMesh out = clean_mesh(m, &r);
  EXPECT_EQ(r.degenerate_faces, 1u);
  EXPECT_EQ(r.split_faces, 1u);
  ASSERT_EQ(out.triangles.size(), 4u);
  EXPECT_EQ(out.triangles[0], (std::array<int32_t, 3>{0, 2, 3}));  // the halves in the split face's place
  EXPECT_EQ(out.triangles[1], (std::array<int32_t, 3>{2, 1, 3}));
  const MeshStats s = compute_stats(to_polygon_mesh(out));
  EXPECT_EQ(s.boundary_loops, 1u);
  EXPECT_EQ(s.boundary_edges, 4u);
  EXPECT_EQ(s.nonmanifold_edges, 0u);
  EXPECT_EQ(s.euler_characteristic, 1);
  // Without the triangle across (a boundary there), it is only dropped.
  PolygonMesh open = soup({{0, 0, 0}, {2, 0, 0}, {1, 0, 0}, {1, -1, 0}}, {{1, 0, 2}, {0, 3, 2}, {2, 3, 1}});
  CleanReport r2;
  TriangleMesh open_out = clean_mesh(open, &r2);
  EXPECT_EQ(r2.degenerate_faces, 1u);
  EXPECT_EQ(r2.split_faces, 0u);
  ASSERT_EQ(open_out.triangles.size(), 2u);
  EXPECT_EQ(compute_stats(to_polygon_mesh(open_out)).boundary_loops, 1u);
}

TEST(MeshClean, TriangulatesPolygonsWithoutDuplicatingEdges) {
  // Two quads sharing two consecutive edges (the corpus's beast.obj has this):
  // a diagonal a naive fan would add twice must be avoided.
  PolygonMesh m = soup({{0, 0, 0}, {1, 0, 0.1}, {1, 1, 0}, {0, 1, 0.1}, {2, 0.5, 0}, {-1, 0.5, 0}},
                       {{0, 1, 2, 3}, {2, 1, 0, 4}});
  CleanReport r;
  TriangleMesh out = clean_mesh(m, &r);
  EXPECT_EQ(r.polygons_triangulated, 2u);
  ASSERT_EQ(out.triangles.size(), 4u);
  const MeshStats s = compute_stats(to_polygon_mesh(out));
  EXPECT_EQ(s.nonmanifold_edges, 0u);
  std::set<std::array<int32_t, 3>> unique;
  for (auto t : out.triangles) {
    std::sort(t.begin(), t.end());
    EXPECT_TRUE(unique.insert(t).second) << "duplicate triangle";
  }
}

TEST(MeshClean, PentagonBecomesThreeTrianglesWithShortDiagonals) {
  PolygonMesh m = soup({{0, 0, 0}, {2, 0, 0}, {2.5, 1, 0}, {1, 2, 0}, {-0.5, 1, 0}}, {{0, 1, 2, 3, 4}});
  TriangleMesh out = clean_mesh(m);
  ASSERT_EQ(out.triangles.size(), 3u);
  double area = 0;
  for (const auto& t : out.triangles)
    area += 0.5 * (out.positions[t[1]] - out.positions[t[0]]).cross(out.positions[t[2]] - out.positions[t[0]]).z();
  EXPECT_NEAR(area, 4.0, 1e-12);  // shoelace area, same orientation
}

TEST(MeshClean, CorpusBeastBecomesClosedManifoldGenusZero) {
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not present";
  auto raw = read_polygon_mesh(test::corpus_path("beast.obj"));
  ASSERT_TRUE(raw.ok()) << raw.status().message();
  CleanReport r;
  const TriangleMesh out = clean_mesh(raw.value(), &r);
  EXPECT_EQ(r.polygons_triangulated, 32228u + 10u + 2u);
  const MeshStats s = compute_stats(to_polygon_mesh(out));
  EXPECT_EQ(s.faces, s.triangles);
  EXPECT_EQ(s.faces, 64618u);
  EXPECT_TRUE(s.is_closed());
  EXPECT_TRUE(s.is_manifold());
  EXPECT_EQ(s.orientation_inconsistent_edges, 0u);
  EXPECT_EQ(s.genus, 0);
}

}  // namespace
}  // namespace srcodec
