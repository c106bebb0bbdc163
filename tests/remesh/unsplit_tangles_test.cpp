#include "remesh/unsplit_tangles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>

#include "tests/test_util.h"

namespace srcodec {
namespace {

// The unit square as a base mesh of 4 x 4 cells, split twice everywhere,
// every vertex at its dyadic place.
SemiRegularMesh two_levels_of_the_square() {
  const TriangleMesh base = test::flat_square(4);
  auto created = TriangleHierarchy::create(static_cast<int32_t>(base.positions.size()), base.triangles);
  EXPECT_TRUE(created.ok());
  SemiRegularMesh m{base, std::move(created).value(), {}, 2, {}};
  for (int32_t level = 0; level < 2; ++level) {
    const size_t count = m.hierarchy.nodes().size();
    for (size_t n = 0; n < count; ++n)
      if (m.hierarchy.nodes()[n].level == level) m.hierarchy.split(static_cast<int32_t>(n));
  }
  m.positions = base.positions;
  for (int32_t v = static_cast<int32_t>(base.positions.size()); v < m.hierarchy.vertex_count(); ++v) {
    const std::array<int32_t, 2> e = m.hierarchy.parent_edge(v);
    m.positions.push_back(0.5 * (m.positions[static_cast<size_t>(e[0])] + m.positions[static_cast<size_t>(e[1])]));
  }
  return m;
}

// The level-2 vertex at (x, y) (a midpoint of a level-1 edge).
int32_t vertex_at(const SemiRegularMesh& m, double x, double y) {
  for (size_t v = 0; v < m.positions.size(); ++v)
    if ((m.positions[v] - Eigen::Vector3d(x, y, 0.0)).norm() < 1e-12) return static_cast<int32_t>(v);
  return -1;
}

// The finest level's folded triangles and pleats, judged as unsplit_tangles
// judges them over the flat square (every side +z).
FoldCount finest_tangles(const SemiRegularMesh& m) {
  return count_by_sides(m.positions, std::vector<Eigen::Vector3d>(m.positions.size(), Eigen::Vector3d::UnitZ()),
                        m.hierarchy.level_triangles(m.levels));
}

// How many triangles use each edge of `triangles`.
std::map<std::pair<int32_t, int32_t>, int> edge_uses(const std::vector<std::array<int32_t, 3>>& triangles) {
  std::map<std::pair<int32_t, int32_t>, int> uses;
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) ++uses[std::minmax(t[c], t[(c + 1) % 3])];
  return uses;
}

// A vertex of the finest level pushed past its neighbours folds triangles
// of two siblings' families; they are taken out by leaving whole the star
// of level 1 around a corner of their parents. The result is still closed
// conformingly (every edge inside the square used twice), the pushed vertex
// is gone, nothing is folded, and the coarser level is the same.
TEST(UnsplitTangles, LeavesWholeTheStarAroundAFoldedChild) {
  const TriangleMesh input = test::flat_square(60);
  SemiRegularMesh mesh = two_levels_of_the_square();
  const int32_t pushed = vertex_at(mesh, 0.5, 0.5625);  // midpoint of a vertical level-1 edge
  ASSERT_GE(pushed, 0);
  ASSERT_EQ(mesh.hierarchy.vertex_level(pushed), 2);
  mesh.positions[static_cast<size_t>(pushed)] += Eigen::Vector3d(0.15, 0.0, 0.0);  // 1.2 level-1 edges

  UnsplitReport report;
  auto result = unsplit_tangles(input, mesh, {}, &report);
  ASSERT_TRUE(result.ok());
  const SemiRegularMesh& out = result.value();
  EXPECT_GT(report.before.folded_by_nearest_input, 0u);
  EXPECT_EQ(finest_tangles(mesh).folded_by_nearest_input, report.before.folded_by_nearest_input);
  EXPECT_EQ(finest_tangles(out).folded_by_nearest_input, 0u);
  EXPECT_EQ(finest_tangles(out).pleats, 0u);
  EXPECT_EQ(report.stars, 1u);
  EXPECT_GE(report.undone, 6u);  // a star of the regular grid has 6 triangles
  EXPECT_LT(out.hierarchy.level_triangles(2).size(), mesh.hierarchy.level_triangles(2).size());
  EXPECT_EQ(out.levels, 2);
  EXPECT_EQ(std::count(out.positions.begin(), out.positions.end(), mesh.positions[static_cast<size_t>(pushed)]), 0);
  EXPECT_LT(out.positions.size(), mesh.positions.size());

  const std::vector<std::array<int32_t, 3>> finest = out.hierarchy.level_triangles(2);
  size_t rim = 0;
  for (const auto& [edge, uses] : edge_uses(finest)) {
    const Eigen::Vector3d mid = 0.5 * (out.positions[static_cast<size_t>(edge.first)] +
                                       out.positions[static_cast<size_t>(edge.second)]);
    const bool on_square = mid.x() < 1e-12 || mid.y() < 1e-12 || mid.x() > 1 - 1e-12 || mid.y() > 1 - 1e-12;
    EXPECT_EQ(uses, on_square ? 1 : 2) << "edge " << edge.first << "-" << edge.second;
    rim += on_square;
  }
  EXPECT_EQ(rim, 4u * 16u);  // the square's boundary as finely split as before
  const TriangleMesh coarse_before = mesh.level_mesh(1), coarse_after = out.level_mesh(1);
  EXPECT_EQ(coarse_after.positions, coarse_before.positions);
  EXPECT_EQ(coarse_after.triangles, coarse_before.triangles);

  // Deterministic.
  auto again = unsplit_tangles(input, mesh, {}, nullptr);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again.value().positions, out.positions);
  EXPECT_EQ(again.value().hierarchy.level_triangles(2), finest);
}

// Children reaching out of their parent by more than UnsplitOptions::max_reach
// times its edge stay split (the level above would cut that off), and a mesh
// with nothing tangled is returned as it is.
TEST(UnsplitTangles, KeepsChildrenThatReachFarAndUntangledMeshes) {
  const TriangleMesh input = test::flat_square(60);
  SemiRegularMesh mesh = two_levels_of_the_square();
  UnsplitReport report;
  auto untouched = unsplit_tangles(input, mesh, {}, &report);
  ASSERT_TRUE(untouched.ok());
  EXPECT_EQ(report.before.folded_by_nearest_input + report.before.pleats, 0u);
  EXPECT_EQ(report.stars, 0u);
  EXPECT_EQ(untouched.value().positions, mesh.positions);

  const int32_t pushed = vertex_at(mesh, 0.5, 0.5625);
  ASSERT_GE(pushed, 0);
  mesh.positions[static_cast<size_t>(pushed)] += Eigen::Vector3d(0.3, 0.0, 0.0);  // 2.4 level-1 edges
  auto far = unsplit_tangles(input, mesh, {}, &report);
  ASSERT_TRUE(far.ok());
  // (Triangles in a pleat with the pushed vertex's may be taken out; the
  // vertex and its folded triangles stay.)
  const Eigen::Vector3d& at = mesh.positions[static_cast<size_t>(pushed)];
  EXPECT_GT(report.before.folded_by_nearest_input, 0u);
  EXPECT_EQ(std::count(far.value().positions.begin(), far.value().positions.end(), at), 1);
  EXPECT_GT(finest_tangles(far.value()).folded_by_nearest_input, 0u);
  UnsplitOptions wider;
  wider.max_reach = 3.0;
  auto allowed = unsplit_tangles(input, mesh, wider, &report);
  ASSERT_TRUE(allowed.ok());
  EXPECT_EQ(std::count(allowed.value().positions.begin(), allowed.value().positions.end(), at), 0);
  EXPECT_EQ(finest_tangles(allowed.value()).folded_by_nearest_input, 0u);
}

// A vertex of level 1 pushed past its neighbours folds triangles of both
// levels. With UnsplitOptions::coarser the corners of the folded level-1
// triangles get stars too (more of them than around the finest level's
// folds alone), and level 1 keeps its triangles.
TEST(UnsplitTangles, CoarserLevelsTooFreeTheCornersOfTheirFolds) {
  const TriangleMesh input = test::flat_square(60);
  SemiRegularMesh mesh = two_levels_of_the_square();
  const int32_t pushed = vertex_at(mesh, 0.375, 0.5);
  ASSERT_GE(pushed, 0);
  ASSERT_EQ(mesh.hierarchy.vertex_level(pushed), 1);
  mesh.positions[static_cast<size_t>(pushed)] += Eigen::Vector3d(0.1, -0.1, 0.0);  // across a diagonal
  const std::vector<std::array<int32_t, 3>> coarse = mesh.hierarchy.level_triangles(1);
  ASSERT_GT(count_by_sides(mesh.positions, std::vector<Eigen::Vector3d>(mesh.positions.size(), Eigen::Vector3d::UnitZ()),
                           coarse).folded_by_nearest_input,
            0u);

  UnsplitReport finest_only, with_coarser;
  auto a = unsplit_tangles(input, mesh, {}, &finest_only);
  UnsplitOptions coarser;
  coarser.coarser = true;
  auto b = unsplit_tangles(input, mesh, coarser, &with_coarser);
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(b.ok());
  EXPECT_GT(finest_only.stars, 0u);
  EXPECT_GT(with_coarser.stars, finest_only.stars);
  EXPECT_GT(with_coarser.undone, finest_only.undone);
  const TriangleMesh before = mesh.level_mesh(1), after = b.value().level_mesh(1);
  EXPECT_EQ(after.positions, before.positions);
  EXPECT_EQ(after.triangles, before.triangles);
}

}  // namespace
}  // namespace srcodec
