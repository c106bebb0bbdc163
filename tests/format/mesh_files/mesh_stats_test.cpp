#include "format/mesh_files/mesh_stats.h"

#include <gtest/gtest.h>

#include "format/mesh_files/mesh_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

MeshStats stats_of(const TriangleMesh& m) { return compute_stats(to_polygon_mesh(m)); }

TEST(MeshStats, ClosedShapes) {
  const MeshStats cube = stats_of(test::unit_cube());
  EXPECT_EQ(cube.vertices, 8u);
  EXPECT_EQ(cube.edges, 18u);
  EXPECT_EQ(cube.components, 1u);
  EXPECT_TRUE(cube.is_closed());
  EXPECT_TRUE(cube.is_manifold());
  EXPECT_EQ(cube.orientation_inconsistent_edges, 0u);
  EXPECT_EQ(cube.euler_characteristic, 2);
  EXPECT_EQ(cube.genus, 0);
  EXPECT_NEAR(cube.bbox_diagonal, std::sqrt(3.0), 1e-15);
}

TEST(MeshStats, OpenGridHasOneBoundaryLoop) {
  const MeshStats s = stats_of(test::flat_square(4));
  EXPECT_EQ(s.boundary_edges, 16u);
  EXPECT_EQ(s.boundary_loops, 1u);
  EXPECT_EQ(s.genus, 0);
}

TEST(MeshStats, TorusHasGenusOne) {
  // A 6 x 4 quad torus, triangulated.
  TriangleMesh t;
  const int n = 6, m = 4;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      t.positions.emplace_back((2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u), std::sin(v));
    }
  auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const MeshStats s = stats_of(t);
  EXPECT_TRUE(s.is_closed());
  EXPECT_EQ(s.euler_characteristic, 0);
  EXPECT_EQ(s.genus, 1);
}

TEST(MeshStats, NonManifoldSpots) {
  // Two tetrahedra sharing one vertex: a non-manifold vertex, one component.
  TriangleMesh m = test::tetrahedron();
  TriangleMesh b = test::tetrahedron();
  for (auto& p : b.positions) p = -p;  // vertex 0 stays at the origin
  const auto offset = static_cast<int32_t>(m.positions.size());
  for (size_t i = 1; i < b.positions.size(); ++i) m.positions.push_back(b.positions[i]);
  auto map = [&](int32_t v) { return v == 0 ? 0 : v - 1 + offset; };
  for (const auto& t : b.triangles) m.triangles.push_back({map(t[0]), map(t[1]), map(t[2])});
  MeshStats s = stats_of(m);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.nonmanifold_vertices, 1u);
  EXPECT_EQ(s.nonmanifold_edges, 0u);
  EXPECT_FALSE(s.genus.has_value());

  // Three triangles on one edge: a non-manifold edge.
  TriangleMesh fin;
  fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  s = stats_of(fin);
  EXPECT_EQ(s.nonmanifold_edges, 1u);
  EXPECT_EQ(s.boundary_loops, 1u);  // the six outer edges touch each other
}

TEST(MeshStats, CountsFlippedFaces) {
  TriangleMesh m = test::unit_cube();
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  EXPECT_EQ(stats_of(m).orientation_inconsistent_edges, 3u);
}

// The corpus figures its MANIFEST.md states, as `srcodec info` must report them.
struct CorpusCase {
  const char* file;
  size_t vertices, faces, components, boundary_loops, nonmanifold_vertices;
  long genus;  // -1: undefined
};

class CorpusStats : public ::testing::TestWithParam<CorpusCase> {};

TEST_P(CorpusStats, MatchManifest) {
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not present";
  const CorpusCase& c = GetParam();
  auto raw = read_polygon_mesh(test::corpus_path(c.file));
  ASSERT_TRUE(raw.ok()) << raw.status().message();
  const MeshStats s = compute_stats(raw.value());
  EXPECT_EQ(s.vertices, c.vertices);
  EXPECT_EQ(s.faces, c.faces);
  EXPECT_EQ(s.components, c.components);
  EXPECT_EQ(s.boundary_loops, c.boundary_loops);
  EXPECT_EQ(s.nonmanifold_vertices, c.nonmanifold_vertices);
  if (c.genus < 0) EXPECT_FALSE(s.genus.has_value());
  else EXPECT_EQ(s.genus, c.genus);
}

INSTANTIATE_TEST_SUITE_P(Manifest, CorpusStats,
                         ::testing::Values(CorpusCase{"ogre.obj", 62194, 124008, 44, 12, 3, -1},
                                           CorpusCase{"lionstatue.obj", 31825, 63338, 1, 1, 0, 3},
                                           CorpusCase{"rocker-arm.obj", 10044, 20088, 1, 0, 0, 1},
                                           CorpusCase{"stanford-bunny.obj", 35947, 69451, 1, 5, 0, 0},
                                           CorpusCase{"beast.obj", 32311, 32364, 1, 0, 0, 0},
                                           CorpusCase{"spot.obj", 2930, 5856, 1, 0, 0, 0}),
                         [](const auto& test_param) {
                           std::string n = test_param.param.file;
                           for (auto& ch : n) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
                           return n;
                         });

TEST(MeshStats, BundledSampleAlways) {
  auto raw = read_polygon_mesh(test::source_path("data/spot.obj"));
  ASSERT_TRUE(raw.ok()) << raw.status().message();
  const MeshStats s = compute_stats(raw.value());
  EXPECT_EQ(s.vertices, 2930u);
  EXPECT_EQ(s.faces, 5856u);
  EXPECT_TRUE(s.is_closed());
  EXPECT_TRUE(s.is_manifold());
  EXPECT_EQ(s.genus, 0);
  EXPECT_NEAR(s.bbox_diagonal, 2.58809, 1e-5);
}

}  // namespace
}  // namespace srcodec
