// butterfly_subdivide: the wavelet's prediction as a subdivision of a plain
// mesh, against OpenMesh's ModifiedButterflyT (as remesh/oversample.cpp runs
// it) without creases, and keeping creases sharp with them.
#include "wavelet/butterfly_subdivision.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "format/mesh.h"
#include "format/mesh_files/mesh_io.h"
#include "remesh/components.h"
#include "remesh/oversample.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using Eigen::Vector3d;
using Edges = std::vector<std::array<int32_t, 2>>;
using Triangle = std::array<int32_t, 3>;

// Per vertex of `a`, the vertex of `b` within `tolerance` of it (each used
// once), found through a grid of cells much larger than the tolerance and
// much smaller than an edge; -1 where there is none.
std::vector<int32_t> match_by_position(const TriangleMesh& a, const TriangleMesh& b, double cell, double tolerance) {
  std::map<std::array<int64_t, 3>, std::vector<int32_t>> grid;
  auto key = [cell](const Vector3d& p) {
    return std::array<int64_t, 3>{static_cast<int64_t>(std::floor(p.x() / cell)),
                                  static_cast<int64_t>(std::floor(p.y() / cell)),
                                  static_cast<int64_t>(std::floor(p.z() / cell))};
  };
  for (size_t i = 0; i < b.positions.size(); ++i) grid[key(b.positions[i])].push_back(static_cast<int32_t>(i));
  std::vector<int32_t> out(a.positions.size(), -1);
  std::vector<char> used(b.positions.size(), 0);
  for (size_t i = 0; i < a.positions.size(); ++i) {
    const std::array<int64_t, 3> k = key(a.positions[i]);
    double best = tolerance;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (int32_t j : it->second) {
            const double d = (a.positions[i] - b.positions[j]).norm();
            if (!used[j] && d <= best) best = d, out[i] = j;
          }
        }
    if (out[i] >= 0) used[out[i]] = 1;
  }
  return out;
}

// Triangles with their smallest vertex first (orientation kept), sorted.
std::vector<Triangle> canonical(std::vector<Triangle> triangles) {
  for (Triangle& t : triangles) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// `ours` and `theirs` are the same mesh: a vertex of `theirs` within
// `tolerance` times the bounding-box diagonal of each vertex of `ours`, and
// the same triangles through that correspondence.
void expect_same_mesh(const TriangleMesh& ours, const TriangleMesh& theirs, double tolerance, const std::string& what) {
  ASSERT_EQ(ours.positions.size(), theirs.positions.size()) << what;
  ASSERT_EQ(ours.triangles.size(), theirs.triangles.size()) << what;
  const double diag = bounding_box_diagonal(theirs.positions);
  const std::vector<int32_t> match = match_by_position(ours, theirs, 1e-6 * diag, tolerance * diag);
  const size_t unmatched = static_cast<size_t>(std::count(match.begin(), match.end(), -1));
  ASSERT_EQ(unmatched, 0u) << what << ": vertices with no counterpart within " << tolerance << " of the diagonal";
  std::vector<Triangle> mapped = ours.triangles;
  for (Triangle& t : mapped)
    for (int32_t& v : t) v = match[v];
  EXPECT_TRUE(canonical(mapped) == canonical(theirs.triangles)) << what << ": different triangles";
}

void expect_same_as_openmesh(const TriangleMesh& mesh, int32_t steps, const std::string& what) {
  const auto ours = butterfly_subdivide(mesh, steps);
  ASSERT_TRUE(ours.ok()) << what << ": " << ours.status().message();
  const auto theirs = oversample(mesh, OversampleScheme::kButterfly, steps);
  ASSERT_TRUE(theirs.ok()) << what << ": " << theirs.status().message();
  // The input's vertices keep their ids and positions in both.
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    ASSERT_EQ(ours->mesh.positions[i], mesh.positions[i]) << what;
    ASSERT_EQ(theirs->positions[i], mesh.positions[i]) << what;
  }
  expect_same_mesh(ours->mesh, theirs.value(), 1e-12, what + ", " + std::to_string(steps) + " steps");
  EXPECT_TRUE(ours->crease_edges.empty());
}

// The mesh's largest manifold component, as the remesher oversamples it.
TriangleMesh largest_component(const std::string& path) {
  const auto input = read_triangle_mesh(path);
  EXPECT_TRUE(input.ok()) << path << ": " << input.status().message();
  if (!input.ok()) return {};
  auto parts = split_into_manifold_components(input.value());
  EXPECT_TRUE(parts.ok()) << parts.status().message();
  if (!parts.ok() || parts->empty()) return {};
  size_t best = 0;
  for (size_t c = 1; c < parts->size(); ++c)
    if (parts.value()[c].mesh.triangles.size() > parts.value()[best].mesh.triangles.size()) best = c;
  return parts.value()[best].mesh;
}

TEST(ButterflySubdivision, SameAsOpenMeshModifiedButterfly) {
  expect_same_as_openmesh(test::icosphere(0, 1.0), 3, "icosahedron");
  expect_same_as_openmesh(test::flat_square(4), 2, "open square");
  expect_same_as_openmesh(test::waisted_ring(24, 8), 1, "ring (genus 1)");
  expect_same_as_openmesh(test::tetrahedron(), 3, "tetrahedron");
  expect_same_as_openmesh(largest_component(test::source_path("data/spot.obj")), 2, "spot");
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not found: checked the bundled meshes only";
  // Open, with five holes: the boundary rules too.
  expect_same_as_openmesh(largest_component(test::corpus_path("stanford-bunny.obj")), 1, "stanford-bunny");
  expect_same_as_openmesh(largest_component(test::corpus_path("fandisk.obj")), 2, "fandisk");
}

// The unit cube's 12 edges.
Edges cube_edges(const TriangleMesh& cube) {
  std::set<std::array<int32_t, 2>> out;
  for (const Triangle& t : cube.triangles)
    for (int c = 0; c < 3; ++c) {
      const int32_t a = t[c], b = t[(c + 1) % 3];
      const Vector3d d = cube.positions[a] - cube.positions[b];
      if ((d.array() != 0.0).count() == 1) out.insert({std::min(a, b), std::max(a, b)});
    }
  return {out.begin(), out.end()};
}

double cube_surface_distance(const Vector3d& p) {
  const Vector3d inside = p.cwiseMax(0.0).cwiseMin(1.0);
  const double outside = (p - inside).norm();
  return outside > 0.0 ? outside : std::min(p.minCoeff(), 1.0 - p.maxCoeff());
}

// Creases: the cube stays the cube, its crease edges are handed on (96
// edges along its 12 edges after 3 steps), and subdividing once then twice
// more with the returned creases gives the same mesh as three steps.
TEST(ButterflySubdivision, CreasesStaySharpAndCarryOver) {
  const TriangleMesh cube = test::unit_cube();
  const Edges creases = cube_edges(cube);
  ASSERT_EQ(creases.size(), 12u);
  const auto sharp = butterfly_subdivide(cube, 3, creases);
  ASSERT_TRUE(sharp.ok()) << sharp.status().message();
  double worst = 0.0;
  for (const Vector3d& p : sharp->mesh.positions) worst = std::max(worst, cube_surface_distance(p));
  EXPECT_LT(worst, 1e-12);
  ASSERT_EQ(sharp->crease_edges.size(), 96u);
  EXPECT_TRUE(std::is_sorted(sharp->crease_edges.begin(), sharp->crease_edges.end()));
  for (const auto& [a, b] : sharp->crease_edges) {
    ASSERT_LT(a, b);
    // Both ends on one cube edge: their difference along one axis only.
    const Vector3d d = sharp->mesh.positions[a] - sharp->mesh.positions[b];
    EXPECT_EQ((d.array().abs() > 1e-12).count(), 1);
  }
  const auto round = butterfly_subdivide(cube, 3);
  ASSERT_TRUE(round.ok());
  double rounded = 0.0;
  for (const Vector3d& p : round->mesh.positions) rounded = std::max(rounded, cube_surface_distance(p));
  EXPECT_GT(rounded, 0.01);

  const auto once = butterfly_subdivide(cube, 1, creases);
  ASSERT_TRUE(once.ok());
  const auto twice_more = butterfly_subdivide(once->mesh, 2, once->crease_edges);
  ASSERT_TRUE(twice_more.ok()) << twice_more.status().message();
  expect_same_mesh(twice_more->mesh, sharp->mesh, 1e-14, "1 + 2 steps against 3");
  // Zero steps: the mesh and its creases as they were.
  const auto none = butterfly_subdivide(cube, 0, creases);
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none->mesh.positions, cube.positions);
  EXPECT_EQ(none->mesh.triangles, cube.triangles);
  EXPECT_EQ(none->crease_edges, creases);
}

TEST(ButterflySubdivision, RefusesBadInput) {
  const TriangleMesh cube = test::unit_cube();
  EXPECT_EQ(butterfly_subdivide(cube, -1).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(butterfly_subdivide(cube, 1, {{0, 7}}).status().code(), StatusCode::kInvalidArgument);  // not an edge
  TriangleMesh twice = cube;
  twice.triangles.push_back(cube.triangles[0]);  // a directed edge used twice
  EXPECT_FALSE(butterfly_subdivide(twice, 1).ok());
}

}  // namespace
}  // namespace srcodec
