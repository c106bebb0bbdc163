#include "remesh/untangle.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "remesh/fit.h"
#include "remesh/geometry.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;

// Two levels over the vertices of a 9 x 9 grid of the unit square: level 1
// every cell, level 0 the cells of the even rows and columns. The input is
// the same square, finer.
struct TwoLevels {
  std::vector<Eigen::Vector3d> positions;
  std::vector<Triangles> levels{2};
  std::vector<char> fixed;  // the boundary
  static int32_t id(int i, int j) { return j * 9 + i; }
  TwoLevels() {
    for (int j = 0; j <= 8; ++j)
      for (int i = 0; i <= 8; ++i) {
        positions.emplace_back(i / 8.0, j / 8.0, 0.0);
        fixed.push_back(i == 0 || j == 0 || i == 8 || j == 8);
      }
    for (int step : {2, 1})
      for (int j = 0; j < 8; j += step)
        for (int i = 0; i < 8; i += step) {
          Triangles& level = levels[step == 2 ? 0 : 1];
          level.push_back({id(i, j), id(i + step, j), id(i + step, j + step)});
          level.push_back({id(i, j), id(i + step, j + step), id(i, j + step)});
        }
  }
};

// A vertex of the finest level only and one of both levels pushed past
// their neighbours fold triangles of both levels; the untangling puts them
// back among their neighbours, and touches nothing far from them.
TEST(Untangle, UnfoldsPushedVertices) {
  const TriangleMesh input = test::flat_square(60);
  TwoLevels grid;
  const std::vector<Eigen::Vector3d> flat = grid.positions;
  grid.positions[static_cast<size_t>(TwoLevels::id(5, 5))] += Eigen::Vector3d(1.7, 0.4, 0.0) / 8.0;  // level 1 only
  grid.positions[static_cast<size_t>(TwoLevels::id(2, 2))] += Eigen::Vector3d(2.6, 0.3, 0.0) / 8.0;  // levels 0 and 1
  std::vector<Eigen::Vector3d> x = grid.positions;
  const UntangleReport report = untangle(input, grid.levels, grid.fixed, &x);
  EXPECT_GT(report.before.folded, 0u);
  EXPECT_GT(report.before.coarser_folded, 0u);
  EXPECT_EQ(report.after.folded, 0u);
  EXPECT_EQ(report.after.pleats, 0u);
  EXPECT_EQ(report.after.coarser_folded, 0u);
  EXPECT_EQ(report.after.coarser_pleats, 0u);
  EXPECT_GE(report.moved, 2u);
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) {
      const size_t v = static_cast<size_t>(TwoLevels::id(i, j));
      const bool near_a_push = (std::abs(i - 5) <= 2 && std::abs(j - 5) <= 2) || (std::abs(i - 2) <= 3 && std::abs(j - 2) <= 2);
      if (grid.fixed[v] || !near_a_push) {
        EXPECT_EQ(x[v], grid.positions[v]) << "vertex " << i << ", " << j;
      }
    }
  // Deterministic.
  std::vector<Eigen::Vector3d> again = grid.positions;
  untangle(input, grid.levels, grid.fixed, &again);
  EXPECT_EQ(again, x);
  // Nothing to untangle: nothing moves.
  std::vector<Eigen::Vector3d> untouched = flat;
  const UntangleReport none = untangle(input, grid.levels, grid.fixed, &untouched);
  EXPECT_EQ(none.moved, 0u);
  EXPECT_EQ(none.before.total(), 0u);
  EXPECT_EQ(untouched, flat);
}

// Four neighbouring vertices pushed by up to an edge each, two swapped, and
// one of both levels pushed past its neighbours fold triangles of both
// levels. With the single
// moves off (no rounds), the joint moves alone unfold them: every triangle
// of both levels faces up again, in the plane, and only the vertices of the
// clusters and their rings move. Without joint moves nothing moves.
TEST(Untangle, JointMovesUnfoldAClusterTogether) {
  const TriangleMesh input = test::flat_square(60);
  TwoLevels grid;
  const int pushed[][2] = {{4, 4}, {5, 4}, {4, 5}, {5, 5}};
  const double push[][2] = {{1.083, -0.363}, {-0.536, -0.128}, {1.099, -0.769}, {-0.858, -1.0}};
  for (int i = 0; i < 4; ++i)
    grid.positions[static_cast<size_t>(TwoLevels::id(pushed[i][0], pushed[i][1]))] +=
        Eigen::Vector3d(push[i][0], push[i][1], 0.0) / 8.0;
  std::swap(grid.positions[static_cast<size_t>(TwoLevels::id(1, 7))],
            grid.positions[static_cast<size_t>(TwoLevels::id(2, 7))]);
  grid.positions[static_cast<size_t>(TwoLevels::id(6, 2))] += Eigen::Vector3d(-2.6, 0.3, 0.0) / 8.0;  // both levels
  UntangleOptions options;
  options.rounds = 0;
  std::vector<Eigen::Vector3d> x = grid.positions;
  const UntangleReport report = untangle(input, grid.levels, grid.fixed, &x, options);
  EXPECT_GT(report.before.folded, 1u);
  EXPECT_GT(report.before.coarser_folded, 0u);
  EXPECT_GE(report.joint_moved, 2u);
  EXPECT_EQ(report.moved, 0u);
  EXPECT_EQ(report.after.total(), 0u);
  for (const Triangles& level : grid.levels)
    for (const auto& t : level) EXPECT_GT(triangle_normal(x, t).z(), 0.0);
  for (int j = 0; j <= 8; ++j)
    for (int i = 0; i <= 8; ++i) {
      const size_t v = static_cast<size_t>(TwoLevels::id(i, j));
      EXPECT_EQ(x[v].z(), 0.0);
      const bool near_a_push = (i >= 2 && i <= 7 && j >= 2 && j <= 7) || (i <= 4 && j >= 5) || (i >= 3 && j <= 4);
      if (!near_a_push) {
        EXPECT_EQ(x[v], grid.positions[v]) << i << ", " << j;
      }
    }
  options.joint_vertices = 0;
  x = grid.positions;
  EXPECT_EQ(untangle(input, grid.levels, grid.fixed, &x, options).joint_moved, 0u);
  EXPECT_EQ(x, grid.positions);
}

// A fixed vertex stays, folded or not.
TEST(Untangle, LeavesFixedVertices) {
  const TriangleMesh input = test::flat_square(60);
  TwoLevels grid;
  const size_t pushed = static_cast<size_t>(TwoLevels::id(5, 5));
  grid.positions[pushed] += Eigen::Vector3d(1.7, 0.4, 0.0) / 8.0;
  grid.fixed.assign(grid.positions.size(), 1);
  std::vector<Eigen::Vector3d> x = grid.positions;
  const UntangleReport report = untangle(input, grid.levels, grid.fixed, &x);
  EXPECT_GT(report.after.folded, 0u);
  EXPECT_EQ(report.moved, 0u);
  EXPECT_EQ(x, grid.positions);
}

// Where the tangles are: a vertex of both levels pushed at (2, 2) and one of
// the finest level only at (5, 7) tangle two places, each around its push,
// and only the first has coarser folds. The places' counts sum to the
// untangling's own count; with a reach that spans both, they are one place;
// untangled, there is none.
TEST(TangledPlaces, GatherTheTanglesAroundEachPush) {
  const TriangleMesh input = test::flat_square(60);
  TwoLevels grid;
  const Eigen::Vector3d both = grid.positions[static_cast<size_t>(TwoLevels::id(2, 2))];
  const Eigen::Vector3d finest = grid.positions[static_cast<size_t>(TwoLevels::id(5, 7))];
  grid.positions[static_cast<size_t>(TwoLevels::id(2, 2))] += Eigen::Vector3d(2.6, 0.3, 0.0) / 8.0;
  grid.positions[static_cast<size_t>(TwoLevels::id(5, 7))] += Eigen::Vector3d(1.5, 0.2, 0.0) / 8.0;
  std::vector<char> all_fixed(grid.positions.size(), 1);
  std::vector<Eigen::Vector3d> x = grid.positions;
  const UntangleInput sides(input);
  const TangleCount whole = untangle(sides, grid.levels, all_fixed, &x).after;  // counts, moves nothing
  ASSERT_GT(whole.folded, 0u);
  ASSERT_GT(whole.coarser_folded, 0u);

  const std::vector<TangledPlace> places = tangled_places(sides, grid.levels, x, 0.15);
  ASSERT_EQ(places.size(), 2u);
  TangleCount sum;
  for (const TangledPlace& p : places) {
    sum.folded += p.count.folded;
    sum.pleats += p.count.pleats;
    sum.coarser_folded += p.count.coarser_folded;
    sum.coarser_pleats += p.count.coarser_pleats;
    EXPECT_GT(p.radius, 0.0);
    EXPECT_LT(p.radius, 0.3);
  }
  EXPECT_EQ(sum.folded, whole.folded);
  EXPECT_EQ(sum.pleats, whole.pleats);
  EXPECT_EQ(sum.coarser_folded, whole.coarser_folded);
  EXPECT_EQ(sum.coarser_pleats, whole.coarser_pleats);
  const bool first_is_both = (places[0].centre - both).norm() < (places[0].centre - finest).norm();
  const TangledPlace& at_both = places[first_is_both ? 0 : 1];
  const TangledPlace& at_finest = places[first_is_both ? 1 : 0];
  EXPECT_LT((at_both.centre - both).norm(), 0.25);
  EXPECT_LT((at_finest.centre - finest).norm(), 0.25);
  EXPECT_GT(at_both.count.coarser_folded, 0u);
  EXPECT_EQ(at_finest.count.coarser_folded, 0u);
  EXPECT_GT(at_finest.count.folded, 0u);

  const std::vector<TangledPlace> one = tangled_places(sides, grid.levels, x, 2.0);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].count.folded, whole.folded);
  EXPECT_EQ(one[0].count.coarser_folded, whole.coarser_folded);
  EXPECT_TRUE(tangled_places(sides, grid.levels, TwoLevels().positions, 2.0).empty());
}

// A base vertex (fixed == 2) may only move onto input vertices. Pushed past
// its neighbours, onto an input vertex, it folds triangles of both levels;
// it hops back near its place, onto another vertex of its own component of
// the input, though a second component has a vertex nearer its neighbours'
// centroid. With no hops it stays.
TEST(Untangle, BaseVerticesHopOntoInputVerticesOfTheirComponent) {
  TriangleMesh input = test::flat_square(50);  // no vertex at (0.25, 0.25)
  const size_t own = input.positions.size();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.25, 0.25, -1e-4), Eigen::Vector3d(0.26, 0.25, -1e-4),
                                   Eigen::Vector3d(0.25, 0.26, -1e-4)})
    input.positions.push_back(p);
  input.triangles.push_back({static_cast<int32_t>(own), static_cast<int32_t>(own + 1), static_cast<int32_t>(own + 2)});
  TwoLevels grid;
  const size_t v = static_cast<size_t>(TwoLevels::id(2, 2));  // a base vertex: on level 0
  grid.positions[v] = Eigen::Vector3d(29 / 50.0, 14 / 50.0, 0.0);  // an input vertex, past its neighbours
  grid.fixed.assign(grid.positions.size(), 1);
  grid.fixed[v] = 2;
  std::vector<Eigen::Vector3d> x = grid.positions;
  const UntangleReport report = untangle(input, grid.levels, grid.fixed, &x);
  EXPECT_GT(report.before.folded, 0u);
  EXPECT_GT(report.before.coarser_folded, 0u);
  EXPECT_EQ(report.after.total(), 0u);
  EXPECT_LT((x[v] - Eigen::Vector3d(0.25, 0.25, 0.0)).norm(), 0.05);
  const auto on = std::find(input.positions.begin(), input.positions.end(), x[v]);
  EXPECT_LT(static_cast<size_t>(on - input.positions.begin()), own) << "not a vertex of its own component";
  for (size_t u = 0; u < x.size(); ++u)
    if (u != v) {
      EXPECT_EQ(x[u], grid.positions[u]);
    }
  UntangleOptions no_hops;
  no_hops.input_vertex_hops = 0;
  std::vector<Eigen::Vector3d> stays = grid.positions;
  untangle(input, grid.levels, grid.fixed, &stays, no_hops);
  EXPECT_EQ(stays, grid.positions);
}

// Vertex v over a ring of fixed vertices 0 .. ring - 1 (every other vertex
// is fixed too) on a flat input, untangled: its folded fan must unfold.
// Returns the fan.
Triangles untangle_fan(std::vector<Eigen::Vector3d>* x, int32_t v, int32_t ring) {
  const TriangleMesh input = test::flat_square(60);
  std::vector<Triangles> levels(1);
  for (int32_t i = 0; i < ring; ++i) levels[0].push_back({v, i, (i + 1) % ring});
  std::vector<char> fixed(x->size(), 1);
  fixed[static_cast<size_t>(v)] = 0;
  const UntangleReport report = untangle(input, levels, fixed, x);
  EXPECT_GT(report.before.folded, 0u);
  EXPECT_EQ(report.after.folded, 0u);
  EXPECT_EQ(report.after.pleats, 0u);
  return levels[0];
}

// Four vertices pushed up to three cells away fold triangles of both
// levels. With the joint moves off, the single moves leave one tangled; the
// wider search, which also tries the input vertices nearest each vertex and
// nearest its neighbours' centroid (128 each), unfolds every triangle.
TEST(Untangle, WideSearchUnfoldsWhereTheNearOneStops) {
  const TriangleMesh input = test::flat_square(60);
  TwoLevels grid;
  const int pushed[][2] = {{5, 5}, {6, 1}, {6, 5}, {1, 6}};
  const double push[][2] = {{2.65, -2.72}, {-2.08, -0.36}, {-2.25, -1.96}, {-0.33, -0.4}};
  for (int i = 0; i < 4; ++i)
    grid.positions[static_cast<size_t>(TwoLevels::id(pushed[i][0], pushed[i][1]))] +=
        Eigen::Vector3d(push[i][0], push[i][1], 0.0) / 8.0;
  UntangleOptions options;
  options.joint_vertices = 0;
  std::vector<Eigen::Vector3d> near = grid.positions;
  const UntangleReport without = untangle(input, grid.levels, grid.fixed, &near, options);
  EXPECT_GT(without.before.total(), 10u);
  EXPECT_GT(without.after.total(), 0u);
  options.wide_candidates = 128;
  std::vector<Eigen::Vector3d> wide = grid.positions;
  const UntangleReport with = untangle(input, grid.levels, grid.fixed, &wide, options);
  EXPECT_EQ(with.after.total(), 0u);
  for (const Triangles& level : grid.levels)
    for (const auto& t : level) EXPECT_GT(triangle_normal(wide, t).z(), 0.0);
  for (size_t v = 0; v < wide.size(); ++v)
    if (grid.fixed[v]) {
      EXPECT_EQ(wide[v], grid.positions[v]);
    }
}

// A vertex pulled out of a notched ring of fixed neighbours: toward their
// centroid, toward each of them and on the input vertices nearest the
// centroid its triangles stay folded (the notch at (0.54, 0.40) hides the
// centroid's side), but a small region left of the notch unfolds them all.
// The linear program finds it.
TEST(Untangle, FindsTheFoldFreeRegionOfANotchedRing) {
  std::vector<Eigen::Vector3d> x = {{0.55, 0.68, 0.0}, {0.30, 0.55, 0.0}, {0.56, 0.32, 0.0}, {0.54, 0.40, 0.0},
                                    {0.58, 0.34, 0.0}, {0.70, 0.30, 0.0}, {0.74, 0.35, 0.0}, {0.08, 0.65, 0.0}};
  const int32_t v = 7;
  const Triangles fan = untangle_fan(&x, v, 7);
  // Every triangle of the fan turns counterclockwise, seen from +z.
  for (const auto& t : fan) {
    const Eigen::Vector3d n = (x[static_cast<size_t>(t[1])] - x[static_cast<size_t>(t[0])])
                                  .cross(x[static_cast<size_t>(t[2])] - x[static_cast<size_t>(t[0])]);
    EXPECT_GT(n.z(), 0.0);
  }
  EXPECT_NEAR(x[static_cast<size_t>(v)].z(), 0.0, 1e-12);
}

// A vertex pulled out of a hexagon of fixed neighbours would go back to
// their centroid, but another vertex sits exactly there: it goes elsewhere
// inside, for two vertices at one position are pinched together when the
// output is read back with coincident vertices welded.
TEST(Untangle, MovesNoVertexOntoAnother) {
  std::vector<Eigen::Vector3d> x;
  const double pi = std::acos(-1.0);
  for (int i = 0; i < 6; ++i) x.emplace_back(0.5 + 0.2 * std::cos(i * pi / 3), 0.5 + 0.2 * std::sin(i * pi / 3), 0.0);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // as the untangling sums it: the ring in increasing order
  for (const Eigen::Vector3d& p : x) centroid += p;
  centroid /= 6.0;
  const int32_t v = 6, other = 7;
  x.emplace_back(0.95, 0.5, 0.0);
  x.push_back(centroid);  // in no triangle of this fan, as if in another part of the mesh
  untangle_fan(&x, v, 6);
  EXPECT_NE(x[static_cast<size_t>(v)], x[static_cast<size_t>(other)]);
  EXPECT_EQ(x[static_cast<size_t>(other)], centroid);
}

// Two steep triangles hanging from one edge, both facing up but meeting at
// more than 150 degrees: a pleat, and both its triangles are marked (the
// untangling tries the marked triangles' vertices and their neighbours; its
// own count once lost the second mark). Neither is folded.
TEST(FoldCount, MarksBothTrianglesOfAPleat) {
  const std::vector<Eigen::Vector3d> x = {
      {0.5, 0.0, 0.0}, {0.5, 1.0, 0.0}, {0.45, 0.5, -1.0}, {0.55, 0.5, -1.0}};
  const Triangles ridge = {{0, 1, 2}, {1, 0, 3}};
  const std::vector<Eigen::Vector3d> up(x.size(), Eigen::Vector3d::UnitZ());
  std::vector<char> marked;
  const FoldCount count = count_by_sides(x, up, ridge, &marked);
  EXPECT_EQ(count.folded_by_nearest_input, 0u);
  EXPECT_EQ(count.pleats, 1u);
  EXPECT_EQ(marked, (std::vector<char>{1, 1}));
  // The same judged by the input's normals (a flat square facing up).
  const TriangleMesh input = test::flat_square(10);
  const FoldCount judged = FoldCounter(input)(x, ridge, &marked);
  EXPECT_EQ(judged.pleats, 1u);
  EXPECT_EQ(marked, (std::vector<char>{1, 1}));
}

}  // namespace
}  // namespace srcodec
