#include "remesh/components.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>

#include "format/mesh_files/mesh_clean.h"
#include "format/mesh_files/mesh_io.h"
#include "format/mesh_files/mesh_stats.h"
#include "tests/test_util.h"

// OpenMesh's points default-construct uninitialised on purpose; GCC 12 warns
// about that once add_vertex is inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#pragma GCC diagnostic pop

namespace srcodec {
namespace {

MeshStats stats_of(const TriangleMesh& m) { return compute_stats(to_polygon_mesh(m)); }

double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) v += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]]));
  return v / 6;
}

size_t max_faces_per_edge(const TriangleMesh& m) {
  std::map<std::pair<int32_t, int32_t>, size_t> count;
  size_t most = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) most = std::max(most, ++count[std::minmax(t[k], t[(k + 1) % 3])]);
  return most;
}

// OpenMesh refuses faces on edges that already have two, or that would make
// a vertex complex; every add_face must succeed and every vertex be manifold.
::testing::AssertionResult loads_into_openmesh(const TriangleMesh& m) {
  OpenMesh::TriMesh_ArrayKernelT<> om;
  std::vector<OpenMesh::VertexHandle> handles;
  for (const auto& p : m.positions) handles.push_back(om.add_vertex({float(p.x()), float(p.y()), float(p.z())}));
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    const auto& t = m.triangles[f];
    if (!om.add_face(handles[t[0]], handles[t[1]], handles[t[2]]).is_valid())
      return ::testing::AssertionFailure() << "OpenMesh rejected triangle " << f;
  }
  for (const auto& vh : om.vertices())
    if (!om.is_manifold(vh)) return ::testing::AssertionFailure() << "vertex " << vh.idx() << " not manifold";
  return ::testing::AssertionSuccess();
}

// True when output triangle f of c, mapped back to input vertices, walks
// input triangle `in` in the same direction (starting at any corner).
bool keeps_orientation(const ComponentMesh& c, size_t f, const std::array<int32_t, 3>& in) {
  const auto& out = c.mesh.triangles[f];
  std::array<int32_t, 3> mapped{c.source_vertex[out[0]], c.source_vertex[out[1]], c.source_vertex[out[2]]};
  for (int r = 0; r < 3; ++r) {
    if (mapped == in) return true;
    std::rotate(mapped.begin(), mapped.begin() + 1, mapped.end());
  }
  return false;
}

// What every component must satisfy: one manifold, consistently oriented
// piece that OpenMesh accepts, whose vertices and triangles map back to the
// input (each triangle is its source, possibly reversed).
void expect_valid_component(const ComponentMesh& c, const TriangleMesh& input) {
  const MeshStats s = stats_of(c.mesh);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.referenced_vertices, c.mesh.positions.size());
  EXPECT_TRUE(s.is_manifold());
  EXPECT_EQ(s.orientation_inconsistent_edges, 0u);
  EXPECT_TRUE(loads_into_openmesh(c.mesh));
  ASSERT_EQ(c.source_vertex.size(), c.mesh.positions.size());
  ASSERT_EQ(c.source_triangle.size(), c.mesh.triangles.size());
  for (size_t v = 0; v < c.source_vertex.size(); ++v) {
    ASSERT_GE(c.source_vertex[v], 0);
    ASSERT_LT(static_cast<size_t>(c.source_vertex[v]), input.positions.size());
    EXPECT_EQ(c.mesh.positions[v], input.positions[c.source_vertex[v]]);
  }
  for (size_t f = 0; f < c.mesh.triangles.size(); ++f) {
    const auto& in = input.triangles.at(c.source_triangle[f]);
    const std::array<int32_t, 3> reversed{in[0], in[2], in[1]};
    EXPECT_TRUE(keeps_orientation(c, f, in) || keeps_orientation(c, f, reversed))
        << "triangle " << f << " does not match input triangle " << c.source_triangle[f];
  }
}

std::vector<ComponentMesh> split(const TriangleMesh& m, ManifoldReport* r) {
  auto result = split_into_manifold_components(m, r);
  EXPECT_TRUE(result.ok()) << result.status().message();
  if (!result.ok()) return {};
  size_t triangles = 0;
  for (const auto& c : result.value()) {
    expect_valid_component(c, m);
    triangles += c.mesh.triangles.size();
  }
  EXPECT_EQ(triangles, m.triangles.size());
  return std::move(result).value();
}

// Appends b to a; vertices of b at exactly a's positions are shared (welded).
TriangleMesh merged(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const auto offset = static_cast<int32_t>(m.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (const auto& t : b.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return clean_mesh(to_polygon_mesh(m));
}

TriangleMesh translated(TriangleMesh m, const Eigen::Vector3d& d) {
  for (auto& p : m.positions) p += d;
  return m;
}

TEST(Components, TwoDisjointTetrahedra) {
  ManifoldReport r;
  const auto parts = split(merged(test::tetrahedron(), translated(test::tetrahedron(), {3, 0, 0})), &r);
  ASSERT_EQ(parts.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const MeshStats s = stats_of(parts[i].mesh);
    EXPECT_TRUE(s.is_closed());
    EXPECT_EQ(s.genus, 0);
    EXPECT_EQ(parts[i].mesh.triangles.size(), 4u);
    EXPECT_EQ(parts[i].source_triangle.front(), static_cast<int32_t>(4 * i));  // ordered by input index
    EXPECT_NEAR(signed_volume(parts[i].mesh), 1.0 / 6, 1e-12);
  }
  EXPECT_EQ(r.nonmanifold_edges_cut, 0u);
  EXPECT_EQ(r.nonmanifold_vertices_split, 0u);
  EXPECT_EQ(r.faces_flipped, 0u);
}

TEST(Components, OrderedBySmallestInputTriangle) {
  // Interleave the triangles of two tetrahedra, the second one's first.
  const TriangleMesh pair = merged(test::tetrahedron(), translated(test::tetrahedron(), {3, 0, 0}));
  TriangleMesh m = pair;
  m.triangles.clear();
  for (int i = 0; i < 4; ++i) {
    m.triangles.push_back(pair.triangles[4 + i]);
    m.triangles.push_back(pair.triangles[i]);
  }
  const auto parts = split(m, nullptr);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].source_triangle, (std::vector<int32_t>{0, 2, 4, 6}));
  EXPECT_EQ(parts[1].source_triangle, (std::vector<int32_t>{1, 3, 5, 7}));
  EXPECT_EQ(parts[0].source_vertex.front(), 4);  // vertices in order of first use
  EXPECT_EQ(parts[0].mesh.positions.front(), Eigen::Vector3d(3, 0, 0));
}

TEST(Components, TetrahedraSharingOneVertexAreSplit) {
  TriangleMesh mirrored = test::tetrahedron();
  for (auto& p : mirrored.positions) p = -p;  // vertex 0 stays at the origin
  for (auto& t : mirrored.triangles) std::swap(t[1], t[2]);  // mirroring turned it inside out
  const TriangleMesh m = merged(test::tetrahedron(), mirrored);
  ASSERT_EQ(m.positions.size(), 7u);
  ASSERT_EQ(stats_of(m).nonmanifold_vertices, 1u);

  ManifoldReport r;
  const auto parts = split(m, &r);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(r.nonmanifold_vertices_split, 1u);
  EXPECT_EQ(r.faces_flipped, 0u);
  for (const auto& c : parts) {
    const MeshStats s = stats_of(c.mesh);
    EXPECT_EQ(c.mesh.positions.size(), 4u);
    EXPECT_TRUE(s.is_closed());
    EXPECT_EQ(s.genus, 0);
    EXPECT_GT(signed_volume(c.mesh), 0);
  }
  // Both copies of the shared vertex map back to it.
  EXPECT_EQ(std::count(parts[0].source_vertex.begin(), parts[0].source_vertex.end(), 0), 1);
  EXPECT_EQ(std::count(parts[1].source_vertex.begin(), parts[1].source_vertex.end(), 0), 1);
}

TEST(Components, FinKeepsTheConsistentPair) {
  // Three triangles on edge 0-1; the first two traverse it in opposite directions.
  TriangleMesh fin;
  fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  ASSERT_EQ(stats_of(fin).nonmanifold_edges, 1u);
  ManifoldReport r;
  const auto parts = split(fin, &r);
  EXPECT_EQ(r.nonmanifold_edges_cut, 1u);
  EXPECT_EQ(r.nonmanifold_vertices_split, 2u);  // vertices 0 and 1: one copy for the pair, one for the third face
  EXPECT_EQ(r.faces_flipped, 0u);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].source_triangle, (std::vector<int32_t>{0, 1}));
  EXPECT_EQ(parts[1].source_triangle, (std::vector<int32_t>{2}));
  EXPECT_EQ(stats_of(parts[0].mesh).edges, 5u);  // the pair still shares its edge
  for (const auto& c : parts) EXPECT_LE(max_faces_per_edge(c.mesh), 2u);
}

TEST(Components, FinWithoutAConsistentPairIsJoinedAndFlipped) {
  TriangleMesh fin;
  fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fin.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}};  // all three run 0 -> 1
  ManifoldReport r;
  const auto parts = split(fin, &r);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].mesh.triangles.size(), 2u);
  EXPECT_EQ(r.faces_flipped, 1u);
  for (const auto& c : parts) EXPECT_LE(max_faces_per_edge(c.mesh), 2u);
}

TEST(Components, CubesSharingAnEdgeSeparate) {
  // Four faces on the edge x = y = 1: each cube keeps its own two.
  const TriangleMesh m = merged(test::unit_cube(), translated(test::unit_cube(), {1, 1, 0}));
  ASSERT_EQ(stats_of(m).nonmanifold_edges, 1u);
  ManifoldReport r;
  const auto parts = split(m, &r);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(r.nonmanifold_edges_cut, 1u);
  EXPECT_EQ(r.nonmanifold_vertices_split, 2u);
  for (const auto& c : parts) {
    const MeshStats s = stats_of(c.mesh);
    EXPECT_EQ(c.mesh.triangles.size(), 12u);
    EXPECT_TRUE(s.is_closed());
    EXPECT_EQ(s.genus, 0);
    EXPECT_NEAR(signed_volume(c.mesh), 1.0, 1e-12);
  }
}

TEST(Components, CubeWithOneFlippedFace) {
  TriangleMesh m = test::unit_cube();
  std::swap(m.triangles[5][1], m.triangles[5][2]);
  ASSERT_EQ(stats_of(m).orientation_inconsistent_edges, 3u);
  ManifoldReport r;
  const auto parts = split(m, &r);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(r.faces_flipped, 1u);
  EXPECT_EQ(stats_of(parts[0].mesh).orientation_inconsistent_edges, 0u);
  EXPECT_NEAR(signed_volume(parts[0].mesh), 1.0, 1e-12);
  for (size_t f = 0; f < m.triangles.size(); ++f) EXPECT_EQ(keeps_orientation(parts[0], f, m.triangles[f]), f != 5);
}

TEST(Components, FlippedFaceFirstStillFlipsOnlyIt) {
  // The breadth-first pass starts at the wrong face; the outward rule undoes that.
  TriangleMesh m = test::unit_cube();
  std::swap(m.triangles[0][1], m.triangles[0][2]);
  ManifoldReport r;
  const auto parts = split(m, &r);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(r.faces_flipped, 1u);
  EXPECT_NEAR(signed_volume(parts[0].mesh), 1.0, 1e-12);
}

TEST(Components, InsideOutCubeTurnsOutward) {
  TriangleMesh m = translated(test::unit_cube(), {100, -50, 7});  // volume must not depend on the origin
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  ManifoldReport r;
  const auto parts = split(m, &r);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(r.faces_flipped, 12u);
  EXPECT_NEAR(signed_volume(translated(parts[0].mesh, {-100, 50, -7})), 1.0, 1e-9);
}

TEST(Components, OpenGridStaysOnePieceInItsOrientation) {
  for (const bool reversed : {false, true}) {
    TriangleMesh m = test::flat_square(6);
    if (reversed)
      for (auto& t : m.triangles) std::swap(t[1], t[2]);
    std::swap(m.triangles[7][1], m.triangles[7][2]);  // one face against the majority
    ManifoldReport r;
    const auto parts = split(m, &r);
    ASSERT_EQ(parts.size(), 1u);
    const MeshStats s = stats_of(parts[0].mesh);
    EXPECT_EQ(s.boundary_loops, 1u);
    EXPECT_EQ(s.genus, 0);
    EXPECT_EQ(r.faces_flipped, 1u);
    for (size_t f = 0; f < m.triangles.size(); ++f)
      EXPECT_EQ(keeps_orientation(parts[0], f, m.triangles[f]), f != 7);
    EXPECT_EQ(parts[0].mesh.positions.size(), 49u);
  }
}

TEST(Components, MoebiusBandIsCutOpenAndReported) {
  // A band of 12 quads with a half twist: no consistent orientation exists.
  TriangleMesh m;
  const int n = 12;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const Eigen::Vector3d center(std::cos(a), std::sin(a), 0), radial = center;
    const Eigen::Vector3d across = std::cos(a / 2) * 0.3 * radial + std::sin(a / 2) * 0.3 * Eigen::Vector3d::UnitZ();
    m.positions.push_back(center - across);
    m.positions.push_back(center + across);
  }
  for (int i = 0; i < n; ++i) {
    const int32_t a0 = 2 * i, b0 = 2 * i + 1;
    int32_t a1 = 2 * ((i + 1) % n), b1 = a1 + 1;
    if (i == n - 1) std::swap(a1, b1);  // the twist: the sides trade places
    m.triangles.push_back({a0, b0, b1});
    m.triangles.push_back({a0, b1, a1});
  }
  const MeshStats before = stats_of(m);
  ASSERT_TRUE(before.is_manifold());
  ASSERT_EQ(before.boundary_loops, 1u);  // a Moebius band has one boundary curve
  ASSERT_GT(before.orientation_inconsistent_edges, 0u);

  ManifoldReport r;
  const auto parts = split(m, &r);
  EXPECT_EQ(r.nonorientable_components, 1u);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_GT(parts[0].mesh.positions.size(), m.positions.size());  // cut open: the seam is duplicated
  EXPECT_EQ(stats_of(parts[0].mesh).genus, 0);                    // now a disc
}

TEST(Components, SourceMapsGiveBackInputPositions) {
  const TriangleMesh m = test::icosphere(2, 1.5);
  const auto parts = split(m, nullptr);
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].mesh.positions.size(), m.positions.size());
  for (size_t f = 0; f < m.triangles.size(); ++f) {
    EXPECT_EQ(parts[0].source_triangle[f], static_cast<int32_t>(f));
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(parts[0].mesh.positions[parts[0].mesh.triangles[f][k]], m.positions[m.triangles[f][k]]);
  }
}

TEST(Components, RejectsBadIndicesAndAcceptsEmpty) {
  TriangleMesh m = test::tetrahedron();
  m.triangles.push_back({0, 1, 4});
  auto bad_index = split_into_manifold_components(m);
  ASSERT_FALSE(bad_index.ok());
  EXPECT_EQ(bad_index.status().code(), StatusCode::kInvalidMesh);
  EXPECT_NE(bad_index.status().message().find("triangle 4"), std::string::npos);

  m.triangles.back() = {0, 1, 1};
  auto repeated = split_into_manifold_components(m);
  ASSERT_FALSE(repeated.ok());
  EXPECT_EQ(repeated.status().code(), StatusCode::kInvalidMesh);

  auto empty = split_into_manifold_components(TriangleMesh{});
  ASSERT_TRUE(empty.ok());
  EXPECT_TRUE(empty.value().empty());
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(ComponentsCorpus, Ogre) {
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not present";
  auto m = read_triangle_mesh(test::corpus_path("ogre.obj"));
  ASSERT_TRUE(m.ok()) << m.status().message();
  const MeshStats input = stats_of(m.value());
  ASSERT_EQ(input.components, 44u);  // after welding, as `srcodec info` reports
  ASSERT_EQ(input.nonmanifold_vertices, 0u);

  ManifoldReport r;
  const auto start = std::chrono::steady_clock::now();
  auto parts = split_into_manifold_components(m.value(), &r);
  const double seconds = seconds_since(start);
  ASSERT_TRUE(parts.ok()) << parts.status().message();
  std::cout << "ogre: " << m->triangles.size() << " triangles split in " << seconds << " s\n";
  EXPECT_EQ(parts->size(), 44u);
  EXPECT_EQ(r.nonmanifold_edges_cut, 0u);
  EXPECT_EQ(r.nonmanifold_vertices_split, 0u);
  EXPECT_EQ(r.nonorientable_components, 0u);
  size_t triangles = 0, vertices = 0, boundary_loops = 0;
  for (const auto& c : parts.value()) {
    expect_valid_component(c, m.value());
    triangles += c.mesh.triangles.size();
    vertices += c.mesh.positions.size();
    boundary_loops += stats_of(c.mesh).boundary_loops;
  }
  EXPECT_EQ(triangles, m->triangles.size());
  EXPECT_EQ(vertices, m->positions.size());
  EXPECT_EQ(boundary_loops, input.boundary_loops);
}

TEST(ComponentsCorpus, LionStatue) {
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not present";
  auto m = read_triangle_mesh(test::corpus_path("lionstatue.obj"));
  ASSERT_TRUE(m.ok()) << m.status().message();
  ASSERT_EQ(stats_of(m.value()).orientation_inconsistent_edges, 4u);

  ManifoldReport r;
  const auto parts = split(m.value(), &r);
  ASSERT_EQ(parts.size(), 1u);
  const MeshStats s = stats_of(parts[0].mesh);
  EXPECT_EQ(s.orientation_inconsistent_edges, 0u);
  EXPECT_EQ(s.genus, 3);
  EXPECT_EQ(s.boundary_loops, 1u);
  EXPECT_EQ(parts[0].mesh.positions.size(), m->positions.size());
  EXPECT_EQ(r.nonorientable_components, 0u);
  EXPECT_GT(r.faces_flipped, 0u);
  EXPECT_LT(r.faces_flipped, m->triangles.size() / 2);  // the majority orientation wins
  std::cout << "lionstatue: " << r.faces_flipped << " faces flipped\n";
}

}  // namespace
}  // namespace srcodec
