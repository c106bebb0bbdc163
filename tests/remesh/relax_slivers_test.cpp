#include "remesh/relax_slivers.h"

#include <gtest/gtest.h>

#include <cmath>

#include "remesh/folds.h"
#include "remesh/geometry.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;

constexpr int kCells = 8;
int32_t at(int i, int j) { return j * (kCells + 1) + i; }

// The finest level is an 8 x 8 grid of the unit square (z = 0, or bent into
// a roof along x = 1/2); the level below it, the grid of its even rows and
// columns. Its boundary is fixed.
struct Grid {
  TriangleMesh finest = test::flat_square(kCells);
  Triangles coarser;
  std::vector<char> fixed;
  explicit Grid(bool roof = false) {
    for (int j = 0; j < kCells; j += 2)
      for (int i = 0; i < kCells; i += 2) {
        coarser.push_back({at(i, j), at(i + 2, j), at(i + 2, j + 2)});
        coarser.push_back({at(i, j), at(i + 2, j + 2), at(i, j + 2)});
      }
    for (Eigen::Vector3d& p : finest.positions) {
      fixed.push_back(p.x() == 0.0 || p.y() == 0.0 || p.x() == 1.0 || p.y() == 1.0);
      if (roof) p.z() = 0.5 - std::abs(p.x() - 0.5);
    }
  }
  double worst_at(int32_t v, const std::vector<Eigen::Vector3d>& p) const {
    double worst = 1.0;
    for (const auto& t : finest.triangles)
      if (t[0] == v || t[1] == v || t[2] == v) worst = std::min(worst, triangle_quality(p[t[0]], p[t[1]], p[t[2]]));
    return worst;
  }
};

TEST(RelaxSlivers, QualityOfEquilateralAndFlatTriangles) {
  EXPECT_NEAR(triangle_quality({0, 0, 0}, {1, 0, 0}, {0.5, std::sqrt(3.0) / 2, 0}), 1.0, 1e-12);
  EXPECT_EQ(triangle_quality({0, 0, 0}, {1, 0, 0}, {2, 0, 0}), 0.0);
  EXPECT_EQ(triangle_quality({1, 1, 1}, {1, 1, 1}, {1, 1, 1}), 0.0);
}

// A vertex of the finest level alone, pushed toward a neighbour, goes back
// to where its triangles are round, in the plane; a vertex of both levels
// pushed the same way and the fixed boundary stay where they are.
TEST(RelaxSlivers, RoundsTheFinestLevelsOwnVertices) {
  const Grid grid;
  const TriangleMesh input = test::flat_square(40);
  const FoldCounter::Sides sides(input);  // keeps a reference to input
  std::vector<Eigen::Vector3d> p = grid.finest.positions;
  const Eigen::Vector3d push(0.8 / kCells, 0.1 / kCells, 0.0);
  p[at(3, 3)] += push;  // the finest level's alone
  p[at(6, 6)] += push;  // both levels'
  const std::vector<Eigen::Vector3d> before = p;
  const double worst_before = grid.worst_at(at(3, 3), p);
  ASSERT_LT(worst_before, 0.5);
  const SliverRelaxReport report = relax_slivers(sides, grid.finest.triangles, grid.coarser, grid.fixed, &p);
  EXPECT_GE(report.moved, 1u);
  EXPECT_LT(report.poor_after, report.poor_before);
  EXPECT_GT(grid.worst_at(at(3, 3), p), 0.8);
  EXPECT_LT((p[at(3, 3)] - grid.finest.positions[at(3, 3)]).norm(), 0.2 / kCells);
  EXPECT_EQ(p[at(3, 3)].z(), 0.0);
  EXPECT_EQ(p[at(6, 6)], before[at(6, 6)]);
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      if (grid.fixed[at(i, j)] || (i % 2 == 0 && j % 2 == 0)) {
        EXPECT_EQ(p[at(i, j)], before[at(i, j)]) << i << ", " << j;
      }
    }
  std::vector<Eigen::Vector3d> up(p.size(), Eigen::Vector3d::UnitZ());
  for (const auto& t : grid.finest.triangles) EXPECT_FALSE(folded(p, up, t));
}

// On the ridge of a roof the input's sides differ by 90 degrees: a vertex
// there stays however thin its triangles, while one on a slope moves.
TEST(RelaxSlivers, LeavesCreasesAlone) {
  const Grid grid(/*roof=*/true);
  const FoldCounter::Sides sides(grid.finest);
  std::vector<Eigen::Vector3d> p = grid.finest.positions;
  const Eigen::Vector3d along(0.0, 0.8 / kCells, 0.0);
  p[at(4, 3)] += along;  // on the ridge
  p[at(1, 3)] += along;  // on the left slope, along it
  const Eigen::Vector3d ridge = p[at(4, 3)];
  ASSERT_LT(grid.worst_at(at(4, 3), p), 0.5);
  const double slope_before = grid.worst_at(at(1, 3), p);
  ASSERT_LT(slope_before, 0.5);
  relax_slivers(sides, grid.finest.triangles, grid.coarser, grid.fixed, &p);
  EXPECT_EQ(p[at(4, 3)], ridge);
  EXPECT_GT(grid.worst_at(at(1, 3), p), slope_before);
}

}  // namespace
}  // namespace srcodec
