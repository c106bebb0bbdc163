#include "remesh/boundary_tips.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "format/mesh_files/mesh_clean.h"
#include "remesh/lbg_sites.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

// The unit square (a 90 x 90 grid) with a slit two grid cells wide from
// y = 0.2 to 0.8 at x = 0.5: two boundary loops, the square's (four turns of
// 90 degrees) and the slit's (two of about 180, at its ends).
TriangleMesh slit_square() {
  const TriangleMesh grid = test::flat_square(90);
  TriangleMesh cut;
  cut.positions = grid.positions;
  for (const auto& t : grid.triangles) {
    const Eigen::Vector3d c = (grid.positions[t[0]] + grid.positions[t[1]] + grid.positions[t[2]]) / 3.0;
    if (!(std::abs(c.x() - 0.5) < 1.0 / 90 && c.y() > 0.2 && c.y() < 0.8)) cut.triangles.push_back(t);
  }
  return clean_mesh(to_polygon_mesh(cut));
}

VoronoiCells cells_of(const TriangleMesh& mesh, size_t sites) {
  LbgOptions options;
  options.target_sites = sites;
  auto cells = lbg_sites(mesh, options);
  EXPECT_TRUE(cells.ok()) << cells.status().message();
  return cells.ok() ? cells.value() : VoronoiCells{};
}

// The sites within `radius` of p.
size_t sites_near(const TriangleMesh& mesh, const VoronoiCells& cells, const Eigen::Vector3d& p, double radius) {
  size_t n = 0;
  for (int32_t s : cells.sites) n += (mesh.positions[static_cast<size_t>(s)] - p).norm() < radius;
  return n;
}

TEST(BoundaryTips, ASiteAtEachEndOfASlitAndNoneAtTheSquaresCorners) {
  const TriangleMesh mesh = slit_square();
  VoronoiCells cells = cells_of(mesh, 30);
  const VoronoiCells before = cells;
  BoundaryTipOptions options;
  options.reach = boundary_tip_reach(mesh, 30);
  EXPECT_NEAR(options.reach, 0.5 * std::sqrt(4.0 / std::sqrt(3.0) * (1.0 - 0.6 * 2.0 / 90) / 60.0), 1e-9);
  const size_t added = add_boundary_tip_sites(mesh, options, &cells);
  const double cell = 1.0 / 90;
  // The slit's ends now hold a site each; LBG's own sites may have been
  // there already, but not at both.
  EXPECT_EQ(sites_near(mesh, cells, {0.5, 0.2, 0.0}, 1.6 * cell), 1u);
  EXPECT_EQ(sites_near(mesh, cells, {0.5, 0.8, 0.0}, 1.6 * cell), 1u);
  EXPECT_GE(added, 1u);
  EXPECT_LE(added, 2u);
  ASSERT_EQ(cells.sites.size(), before.sites.size() + added);
  // No site added at the square's corners or along straight rims: the new
  // sites are the slit's ends.
  for (size_t s = before.sites.size(); s < cells.sites.size(); ++s) {
    const Eigen::Vector3d& p = mesh.positions[static_cast<size_t>(cells.sites[s])];
    EXPECT_NEAR(p.x(), 0.5, 1.6 * cell);
    EXPECT_TRUE(std::abs(p.y() - 0.2) < 1.6 * cell || std::abs(p.y() - 0.8) < 1.6 * cell) << p.transpose();
  }
  // Each new cell holds its site and is taken from the old cell at it: the
  // other cells only lose vertices to it.
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const int32_t now = cells.cell_of[v], was = before.cell_of[v];
    if (now != was) {
      ASSERT_GE(static_cast<size_t>(now), before.sites.size()) << "vertex " << v;
    }
  }
  std::vector<size_t> members(cells.sites.size(), 0);
  for (int32_t c : cells.cell_of) ++members[static_cast<size_t>(c)];
  for (size_t s = 0; s < cells.sites.size(); ++s) {
    EXPECT_GT(members[s], 0u) << "cell " << s;
    EXPECT_EQ(cells.cell_of[static_cast<size_t>(cells.sites[s])], static_cast<int32_t>(s));
  }
  // Run again: the tips are sites now, nothing is added.
  EXPECT_EQ(add_boundary_tip_sites(mesh, options, &cells), 0u);
}

TEST(BoundaryTips, NoneOnASquareAClosedMeshOrWithoutReach) {
  const TriangleMesh square = test::flat_square(40);
  VoronoiCells cells = cells_of(square, 20);
  BoundaryTipOptions options;
  options.reach = boundary_tip_reach(square, 20);
  EXPECT_EQ(add_boundary_tip_sites(square, options, &cells), 0u);  // its corners turn by 90 degrees
  options.min_turn_degrees = 80.0;  // ... which a lower bound takes
  EXPECT_LE(add_boundary_tip_sites(square, options, &cells), 4u);
  for (const Eigen::Vector3d& corner : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0),
                                       Eigen::Vector3d(0, 1, 0)})
    EXPECT_GE(sites_near(square, cells, corner, 1e-9), 1u) << corner.transpose();
  const TriangleMesh sphere = test::icosphere(3, 1.0);
  VoronoiCells round = cells_of(sphere, 20);
  options.reach = boundary_tip_reach(sphere, 20);
  EXPECT_EQ(add_boundary_tip_sites(sphere, options, &round), 0u);
  const TriangleMesh slit = slit_square();
  VoronoiCells cut = cells_of(slit, 30);
  options.reach = 0.0;
  EXPECT_EQ(add_boundary_tip_sites(slit, options, &cut), 0u);
}

}  // namespace
}  // namespace srcodec
