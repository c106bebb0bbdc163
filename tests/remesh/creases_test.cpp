// Creases through the remesher (RemeshOptions::creases) on shapes whose
// creases are known: the crease edges of each level of a hierarchy
// (format/semi_regular/creases.h), the oversampling's halves of crease
// edges, a base mesh whose edges follow a cube's twelve edges, a whole
// remesh whose crease vertices lie on them at every level; a cube of 12
// triangles (all corners), a fold running into the boundary, and a noisy
// sphere (no creases).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "format/semi_regular/creases.h"
#include "remesh/base_creases.h"
#include "remesh/base_mesh.h"
#include "remesh/features.h"
#include "remesh/geometry.h"
#include "remesh/lbg_sites.h"
#include "remesh/oversample.h"
#include "remesh/remesher.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using Edge = std::array<int32_t, 2>;

// Whether p lies on one of the cube [-1, 1]^3's twelve edges (two
// coordinates at +-1).
bool on_cube_edge(const Eigen::Vector3d& p, double tolerance = 1e-9) {
  return (p.cwiseAbs().array() > 1.0 - tolerance).count() >= 2;
}

bool is_cube_corner(const Eigen::Vector3d& p) { return (p.cwiseAbs().array() > 1.0 - 1e-9).count() == 3; }

// A uniform remesh keeping creases, on the input's own vertices.
RemeshOptions crease_options(int levels, size_t base_vertices) {
  RemeshOptions o;
  o.levels = levels;
  o.base_vertices = base_vertices;
  o.uniform = true;
  o.oversample = 0;
  o.creases = CreaseMode::kKeep;
  return o;
}

// The cube's creases as the remesher gives them to the base mesh.
BaseMeshCreases cube_creases(const TriangleMesh& cube) {
  const Features f = detect_features(cube);
  BaseMeshCreases c;
  for (const FeatureEdge& e : f.edges) c.edges.push_back({e.a, e.b});
  c.fixed = f.corners;
  return c;
}

TEST(Creases, LevelCreasesAreTheHalvesOfSplitCreaseEdges) {
  // Two triangles sharing the crease 0-1; only the first is split at level 1.
  auto h = TriangleHierarchy::create(4, {{0, 1, 2}, {1, 0, 3}});
  ASSERT_TRUE(h.ok());
  const std::vector<Edge> base{{0, 1}};
  EXPECT_EQ(crease_edges_up_to(*h, base, 0), base);
  std::vector<int32_t> made;
  h->split(0, &made);  // the first triangle; closure bisects the second
  int32_t middle = -1;
  for (int32_t v : made)
    if (h->parent_edge(v) == std::array<int32_t, 2>{0, 1} || h->parent_edge(v) == std::array<int32_t, 2>{1, 0})
      middle = v;
  ASSERT_GE(middle, 0);
  const std::vector<Edge> level1 = crease_edges_up_to(*h, base, 1);
  EXPECT_EQ(level1, (std::vector<Edge>{{0, middle}, {1, middle}}));
  const std::vector<uint8_t> degree = crease_degrees(*h, level1);
  EXPECT_EQ(degree[middle], 2);
  EXPECT_EQ(degree[0], 1);
  EXPECT_EQ(degree[2], 0);
  EXPECT_TRUE(crease_edges_up_to(*h, {}, 1).empty());
}

TEST(Creases, BaseFollowsCreasesNoShorterThanItsEdges) {
  const TriangleMesh cube = test::grid_cube(6);
  const Features features = detect_features(cube);
  // Area 24: base edges of 40 vertices are 0.83 long, of 4 vertices 2.63,
  // longer than the cube's edges (2).
  EXPECT_NEAR(equilateral_edge_length(24.0, 4), std::sqrt(12.0 / std::sqrt(3.0)), 1e-12);
  BaseCreaseOptions fine;
  fine.base_vertices = 40;
  const BaseMeshCreases kept = base_creases(cube, features, fine);
  EXPECT_EQ(kept.edges.size(), 12u * 6);
  EXPECT_EQ(kept.fixed.size(), 8u);
  BaseCreaseOptions coarse;
  coarse.base_vertices = 4;
  const BaseMeshCreases dropped = base_creases(cube, features, coarse);
  EXPECT_TRUE(dropped.edges.empty());
  EXPECT_TRUE(dropped.fixed.empty());
}

// Two unit squares folded at 90 degrees: one crease of length 1. A base of
// n vertices on area 2 has edges of sqrt(4 / (sqrt(3) n)); at 30 vertices
// 0.28, so the crease is 3.6 base edges, 4.0% of the base's 90 edges:
// followed when asked, not by the automatic choice (kAutoCreaseEdgeShare),
// which a cube (its 12 edges all creases) passes.
TEST(Creases, AutomaticChoiceFollowsCreasesOnlyWhereTheyAreAShareOfTheShape) {
  test::GridBuilder g;
  g.patch(24, [](double u, double v) { return Eigen::Vector3d(-u, v, 0); });
  g.patch(24, [](double u, double v) { return Eigen::Vector3d(0, u, v); });
  BaseCreaseOptions o;
  o.base_vertices = 30;
  EXPECT_NEAR(followable_base_edges(g.mesh, detect_features(g.mesh), o), 1.0 / equilateral_edge_length(2.0, 30),
              1e-9);

  RemeshOptions keep = crease_options(1, 30);
  auto kept = remesh(g.mesh, keep);
  ASSERT_TRUE(kept.ok()) << kept.status().message();
  EXPECT_FALSE(kept->crease_edges.empty());
  RemeshOptions automatic = keep;
  automatic.creases = CreaseMode::kAuto;
  RemeshReport report;
  auto chosen = remesh(g.mesh, automatic, &report);
  ASSERT_TRUE(chosen.ok()) << chosen.status().message();
  EXPECT_TRUE(chosen->crease_edges.empty());
  EXPECT_NEAR(report.crease_edge_share, 1.0 / (equilateral_edge_length(2.0, 30) * 90.0), 1e-9);
  automatic.base_vertices = 6;  // edges 0.62 long: 1.6 base edges of 18, 9.0%
  auto coarse = remesh(g.mesh, automatic, &report);
  ASSERT_TRUE(coarse.ok()) << coarse.status().message();
  EXPECT_FALSE(coarse->crease_edges.empty());
  EXPECT_GT(report.crease_edge_share, kAutoCreaseEdgeShare);
}

TEST(Creases, OversamplingSplitsEachCreaseEdgeAlongItself) {
  const TriangleMesh cube = test::grid_cube(3);
  std::vector<Edge> creases = cube_creases(cube).edges;
  const size_t before = creases.size();
  ASSERT_EQ(before, 12u * 3);
  for (OversampleScheme scheme : {OversampleScheme::kLinear, OversampleScheme::kButterfly}) {
    std::vector<Edge> halves = creases;
    auto fine = oversample(cube, scheme, 2, &halves);
    ASSERT_TRUE(fine.ok()) << fine.status().message();
    EXPECT_EQ(halves.size(), 4 * before);
    std::set<Edge> edges;
    for (const auto& t : fine->triangles)
      for (int c = 0; c < 3; ++c) edges.insert({std::min(t[c], t[(c + 1) % 3]), std::max(t[c], t[(c + 1) % 3])});
    for (const Edge& e : halves) {
      EXPECT_TRUE(edges.count(e)) << e[0] << "-" << e[1] << " is no edge";
      if (scheme == OversampleScheme::kLinear) {
        EXPECT_TRUE(on_cube_edge(fine->positions[e[0]]) && on_cube_edge(fine->positions[e[1]]));
      }
    }
  }
  std::vector<Edge> wrong{{0, static_cast<int32_t>(cube.positions.size()) - 1}};
  EXPECT_FALSE(oversample(cube, OversampleScheme::kLinear, 1, &wrong).ok());
}

TEST(Creases, BaseEdgesFollowTheCubesEdges) {
  const TriangleMesh cube = test::grid_cube(12);
  const BaseMeshCreases creases = cube_creases(cube);
  ASSERT_EQ(creases.fixed.size(), 8u);
  LbgOptions lbg;
  lbg.target_sites = 40;
  auto cells = lbg_sites(cube, lbg);
  ASSERT_TRUE(cells.ok());
  BaseMeshReport report;
  auto base = build_base_mesh(cube, cells->sites, cells->cell_of, &report, creases);
  ASSERT_TRUE(base.ok()) << base.status().message();
  const TriangleMesh& b = base->mesh;
  // Every corner is a base vertex, every base crease edge runs along one of
  // the cube's edges (both ends on it, sharing two coordinates at +-1), and
  // the chains cover the cube's 12 edges: length 24 in all.
  size_t corners = 0;
  for (const auto& p : b.positions) corners += is_cube_corner(p);
  EXPECT_EQ(corners, 8u);
  double length = 0.0;
  for (const auto& [x, y] : base->crease_edges) {
    const Eigen::Vector3d &p = b.positions[x], &q = b.positions[y];
    ASSERT_TRUE(on_cube_edge(p) && on_cube_edge(q));
    EXPECT_EQ(((p.cwiseAbs().array() > 1.0 - 1e-9) && (q.cwiseAbs().array() > 1.0 - 1e-9) &&
               (p.array() * q.array() > 0.0))
                  .count(),
              2)
        << "base crease edge " << x << "-" << y << " cuts across a face";
    length += (p - q).norm();
  }
  EXPECT_NEAR(length, 24.0, 1e-9);
  EXPECT_GT(report.crease_vertices_kept, 8u);
  // Every base triangle lies in one face of the cube: flat faces stay flat.
  for (const auto& t : b.triangles) {
    const Eigen::Vector3d n = (b.positions[t[1]] - b.positions[t[0]]).cross(b.positions[t[2]] - b.positions[t[0]]);
    EXPECT_NEAR(n.cwiseAbs().maxCoeff(), n.norm(), 1e-9 * n.norm());
  }
  // The input's crease points are placed on base crease edges: one
  // barycentric is zero.
  for (const Edge& e : creases.edges)
    for (int32_t v : e) EXPECT_NEAR(base->param[v].bary.minCoeff(), 0.0, 1e-9) << "vertex " << v;
}

TEST(Creases, BaseMeshRefusesCreasesItCannotFollow) {
  const TriangleMesh cube = test::grid_cube(4);
  LbgOptions lbg;
  lbg.target_sites = 10;
  auto cells = lbg_sites(cube, lbg);
  ASSERT_TRUE(cells.ok());
  BaseMeshCreases not_an_edge = cube_creases(cube);
  not_an_edge.edges.push_back({0, static_cast<int32_t>(cube.positions.size()) - 1});
  auto a = build_base_mesh(cube, cells->sites, cells->cell_of, nullptr, not_an_edge);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("not an edge"), std::string::npos) << a.status().message();
  BaseMeshCreases unfixed_corners = cube_creases(cube);
  unfixed_corners.fixed.clear();
  auto b = build_base_mesh(cube, cells->sites, cells->cell_of, nullptr, unfixed_corners);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.status().message().find("not fixed"), std::string::npos) << b.status().message();
}

TEST(Creases, RemeshKeepsEveryCreaseVertexOnTheCubesEdges) {
  const TriangleMesh cube = test::grid_cube(32);
  RemeshOptions o = crease_options(3, 40);
  RemeshReport report;
  auto srm = remesh(cube, o, &report);
  ASSERT_TRUE(srm.ok()) << srm.status().message();
  ASSERT_FALSE(srm->crease_edges.empty());
  EXPECT_EQ(report.base_crease_edges, srm->crease_edges.size());
  for (int32_t level = 0; level <= srm->levels; ++level) {
    const std::vector<Edge> creases = crease_edges_up_to(srm->hierarchy, srm->crease_edges, level);
    double length = 0.0;
    for (const auto& [a, b] : creases) {
      EXPECT_TRUE(on_cube_edge(srm->positions[a]) && on_cube_edge(srm->positions[b]))
          << "level " << level << " crease edge " << a << "-" << b;
      length += (srm->positions[a] - srm->positions[b]).norm();
    }
    EXPECT_NEAR(length, 24.0, 1e-6) << "level " << level;
  }
  // And without creases the remesh's edges cut the cube's corners off.
  o.creases = CreaseMode::kIgnore;
  auto plain = remesh(cube, o);
  ASSERT_TRUE(plain.ok());
  EXPECT_TRUE(plain->crease_edges.empty());
  size_t corners = 0;
  for (const auto& p : plain->positions) corners += is_cube_corner(p);
  EXPECT_LT(corners, 8u);
}

TEST(Creases, AMeshOfCornersIsItsOwnBaseWithItsEdgesAsCreases) {
  RemeshOptions o;  // creases decided by the remesher: a cube is all creases
  o.fit_levels = true;  // 8 vertices: the input is its own base mesh
  auto srm = remesh(test::unit_cube(), o);
  ASSERT_TRUE(srm.ok()) << srm.status().message();
  EXPECT_EQ(srm->levels, 0);
  EXPECT_EQ(srm->crease_edges.size(), 12u);  // not the six face diagonals
}

TEST(Creases, CreaseRunningIntoTheBoundaryStaysOnTheFold) {
  // Two squares folded at 90 degrees along x = 0: the crease ends on the
  // boundary at both ends.
  test::GridBuilder g;
  const int n = 48;
  g.patch(n, [](double u, double v) { return Eigen::Vector3d(-u, v, 0); });
  g.patch(n, [](double u, double v) { return Eigen::Vector3d(0, u, v); });
  RemeshOptions o = crease_options(2, 30);
  auto srm = remesh(g.mesh, o);
  ASSERT_TRUE(srm.ok()) << srm.status().message();
  const std::vector<Edge> creases = crease_edges_up_to(srm->hierarchy, srm->crease_edges, srm->levels);
  ASSERT_FALSE(creases.empty());
  double length = 0.0;
  for (const auto& [a, b] : creases) {
    for (int32_t v : {a, b}) {
      EXPECT_NEAR(srm->positions[v].x(), 0.0, 1e-12);
      EXPECT_NEAR(srm->positions[v].z(), 0.0, 1e-12);
    }
    length += (srm->positions[a] - srm->positions[b]).norm();
  }
  EXPECT_NEAR(length, 1.0, 1e-9);
}

TEST(Creases, NoisySphereHasNoCreasesToKeep) {
  // Noise of a tenth of an edge everywhere: no crease, the same remesh as
  // without features.
  TriangleMesh sphere = test::icosphere(4, 1.0);
  uint64_t state = 7;
  for (auto& p : sphere.positions) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    p *= 1.0 + 0.012 * (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5);
  }
  RemeshOptions o = crease_options(2, 40);
  auto with = remesh(sphere, o);
  o.creases = CreaseMode::kIgnore;
  auto plain = remesh(sphere, o);
  ASSERT_TRUE(plain.ok() && with.ok());
  EXPECT_TRUE(with->crease_edges.empty());
  EXPECT_EQ(with->positions, plain->positions);
}

}  // namespace
}  // namespace srcodec
