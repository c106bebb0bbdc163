#include "remesh/base_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "format/mesh_files/mesh_io.h"
#include "remesh/components.h"
#include "remesh/lbg_sites.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

// A torus around the z axis: nu segments around, nv across the tube.
TriangleMesh torus(int nu, int nv, double big, double small) {
  TriangleMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.positions.emplace_back((big + small * std::cos(v)) * std::cos(u), (big + small * std::cos(v)) * std::sin(u),
                               small * std::sin(v));
    }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

struct Topology {
  int64_t euler = 0;
  int boundary_loops = 0;
  bool manifold = true;  // every directed edge once, every vertex one fan
};

Topology topology(const TriangleMesh& m) {
  Topology t;
  std::set<std::pair<int32_t, int32_t>> directed;
  std::set<std::pair<int32_t, int32_t>> undirected;
  std::map<int32_t, std::vector<std::pair<int32_t, int32_t>>> link;
  std::set<int32_t> used;
  for (const auto& f : m.triangles)
    for (int c = 0; c < 3; ++c) {
      const int32_t a = f[c], b = f[(c + 1) % 3];
      if (!directed.insert({a, b}).second) t.manifold = false;
      undirected.insert(std::minmax(a, b));
      link[a].push_back({b, f[(c + 2) % 3]});
      used.insert(a);
    }
  t.euler = static_cast<int64_t>(used.size()) - static_cast<int64_t>(undirected.size()) +
            static_cast<int64_t>(m.triangles.size());
  // Boundary: directed edges without their reverse; each boundary vertex has
  // one outgoing, so loops are the cycles of that successor map.
  std::map<int32_t, int32_t> successor;
  for (const auto& [a, b] : directed)
    if (!directed.count({b, a})) successor[a] = b;
  std::set<int32_t> seen;
  for (const auto& [a, b] : successor) {
    if (seen.count(a)) continue;
    ++t.boundary_loops;
    for (int32_t x = a; !seen.count(x); x = successor.count(x) ? successor[x] : a) seen.insert(x);
  }
  // One fan per vertex: walk the link from a path start (or anywhere).
  for (auto& [v, edges] : link) {
    std::map<int32_t, int32_t> next(edges.begin(), edges.end());
    std::set<int32_t> ends;
    for (const auto& e : edges) ends.insert(e.second);
    int32_t start = edges[0].first;
    for (const auto& e : edges)
      if (!ends.count(e.first)) start = e.first;
    size_t steps = 0;
    for (int32_t x = start; next.count(x) && steps <= edges.size();) {
      x = next[x];
      ++steps;
      if (x == start) break;
    }
    if (steps != edges.size()) t.manifold = false;
  }
  return t;
}

// How many boundary vertices the base mesh may keep: one per run of
// consecutive boundary vertices of one cell, and up to three on a boundary
// loop that runs through fewer cells (a loop needs three vertices).
size_t boundary_bound(const TriangleMesh& m, const std::vector<int32_t>& cell_of) {
  std::set<std::pair<int32_t, int32_t>> directed;
  for (const auto& t : m.triangles)
    for (int c = 0; c < 3; ++c) directed.insert({t[c], t[(c + 1) % 3]});
  size_t runs = 0;
  for (const auto& [a, b] : directed)
    if (!directed.count({b, a}) && cell_of[a] != cell_of[b]) ++runs;  // a run ends at a boundary edge between cells
  return runs + 3 * static_cast<size_t>(topology(m).boundary_loops);
}

Eigen::Vector3d mapped_point(const BaseMesh& base, const ParamPoint& p) {
  const auto& t = base.mesh.triangles[p.face];
  return p.bary[0] * base.mesh.positions[t[0]] + p.bary[1] * base.mesh.positions[t[1]] +
         p.bary[2] * base.mesh.positions[t[2]];
}

struct Measured {
  double max_distance = 0.0;       // |mapped point - input vertex|, largest
  double max_base_edge = 0.0;      // longest base edge
  double adjacent_fraction = 0.0;  // input edges whose ends map to faces sharing a base vertex
};

// Everything build_base_mesh promises, checked on `base`; also measures the
// map's plausibility figures.
::testing::AssertionResult valid_base_mesh(const TriangleMesh& input, const std::vector<int32_t>& sites,
                                           const BaseMesh& base, const BaseMeshReport& report, Measured* measured) {
  const size_t n = input.positions.size();
  const size_t nb = base.input_vertex.size();
  if (nb != sites.size() + report.promoted_vertices)
    return ::testing::AssertionFailure() << nb << " base vertices for " << sites.size() << " sites and "
                                         << report.promoted_vertices << " promoted";
  if (base.mesh.positions.size() != nb) return ::testing::AssertionFailure() << "positions/input_vertex sizes differ";
  std::set<int32_t> base_set(base.input_vertex.begin(), base.input_vertex.end());
  if (base_set.size() != nb) return ::testing::AssertionFailure() << "an input vertex is two base vertices";
  for (int32_t s : sites)
    if (!base_set.count(s)) return ::testing::AssertionFailure() << "site vertex " << s << " is not a base vertex";
  for (size_t b = 0; b < nb; ++b)
    if (base.mesh.positions[b] != input.positions[base.input_vertex[b]])
      return ::testing::AssertionFailure() << "base vertex " << b << " moved";
  for (const auto& t : base.mesh.triangles)
    for (int32_t v : t)
      if (v < 0 || static_cast<size_t>(v) >= nb) return ::testing::AssertionFailure() << "bad base triangle";

  const Topology ti = topology(input), tb = topology(base.mesh);
  if (!tb.manifold) return ::testing::AssertionFailure() << "base mesh not manifold / consistently oriented";
  if (tb.euler != ti.euler)
    return ::testing::AssertionFailure() << "Euler characteristic " << tb.euler << ", input " << ti.euler;
  if (tb.boundary_loops != ti.boundary_loops)
    return ::testing::AssertionFailure() << tb.boundary_loops << " boundary loops, input " << ti.boundary_loops;
  std::set<int32_t> base_used;
  for (const auto& t : base.mesh.triangles) base_used.insert(t.begin(), t.end());
  if (base_used.size() != nb) return ::testing::AssertionFailure() << "a base vertex has no triangle";

  if (base.param.size() != n) return ::testing::AssertionFailure() << "param has the wrong size";
  for (size_t v = 0; v < n; ++v) {
    const ParamPoint& p = base.param[v];
    if (p.face < 0 || static_cast<size_t>(p.face) >= base.mesh.triangles.size())
      return ::testing::AssertionFailure() << "vertex " << v << " has face " << p.face;
    if (p.bary.minCoeff() < -1e-9 || std::abs(p.bary.sum() - 1.0) > 1e-9)
      return ::testing::AssertionFailure() << "vertex " << v << " has barycentrics " << p.bary.transpose();
  }
  for (size_t b = 0; b < nb; ++b) {
    const ParamPoint& p = base.param[base.input_vertex[b]];
    const auto& t = base.mesh.triangles[p.face];
    bool found = false;
    for (int c = 0; c < 3; ++c)
      if (t[c] == static_cast<int32_t>(b) && p.bary[c] == 1.0) found = true;
    if (!found) return ::testing::AssertionFailure() << "base vertex " << b << " is not at its own corner";
  }

  Measured m;
  for (size_t v = 0; v < n; ++v)
    m.max_distance = std::max(m.max_distance, (mapped_point(base, base.param[v]) - input.positions[v]).norm());
  for (const auto& t : base.mesh.triangles)
    for (int c = 0; c < 3; ++c)
      m.max_base_edge =
          std::max(m.max_base_edge, (base.mesh.positions[t[c]] - base.mesh.positions[t[(c + 1) % 3]]).norm());
  size_t edges = 0, adjacent = 0;
  for (const auto& t : input.triangles)
    for (int c = 0; c < 3; ++c) {
      const int32_t a = t[c], b = t[(c + 1) % 3];
      if (a > b) continue;  // each interior edge once (boundary edges may count once or not; fine for a ratio)
      ++edges;
      const auto& fa = base.mesh.triangles[base.param[a].face];
      const auto& fb = base.mesh.triangles[base.param[b].face];
      bool share = false;
      for (int32_t x : fa)
        for (int32_t y : fb) share = share || x == y;
      adjacent += share;
    }
  m.adjacent_fraction = double(adjacent) / double(edges);
  if (measured) *measured = m;
  return ::testing::AssertionSuccess();
}

VoronoiCells cells_for(const TriangleMesh& m, size_t target) {
  LbgOptions options;
  options.target_sites = target;
  auto cells = lbg_sites(m, options);
  EXPECT_TRUE(cells.ok()) << cells.status().message();
  return cells.ok() ? std::move(cells).value() : VoronoiCells{};
}

struct Built {
  BaseMesh base;
  BaseMeshReport report;
  Measured measured;
};

Built build_and_check(const TriangleMesh& m, const VoronoiCells& cells) {
  Built run;
  auto base = build_base_mesh(m, cells.sites, cells.cell_of, &run.report);
  EXPECT_TRUE(base.ok()) << base.status().message();
  if (!base.ok()) return run;
  run.base = std::move(base).value();
  EXPECT_TRUE(valid_base_mesh(m, cells.sites, run.base, run.report, &run.measured));
  EXPECT_EQ(run.report.collapses + run.report.promoted_vertices, m.positions.size() - cells.sites.size());
  return run;
}

TEST(BaseMesh, IcosphereClosedGenusZero) {
  const TriangleMesh sphere = test::icosphere(4, 1.0);  // 2562 vertices
  for (size_t target : {4, 12, 50, 200}) {
    SCOPED_TRACE(target);
    const VoronoiCells cells = cells_for(sphere, target);
    const Built run = build_and_check(sphere, cells);
    EXPECT_EQ(run.report.promoted_vertices, 0u);
    EXPECT_EQ(run.base.mesh.triangles.size(), 2 * target - 4);
    // Site b is base vertex b.
    for (size_t k = 0; k < target; ++k) EXPECT_EQ(run.base.input_vertex[k], cells.sites[k]);
    // Each image lies on a base triangle near its vertex: measured 0.75,
    // 0.22, 0.077, 0.023 for longest base edges 1.66, 1.12, 0.72, 0.43.
    EXPECT_LT(run.measured.max_distance, 0.5 * run.measured.max_base_edge);
    EXPECT_GE(run.measured.adjacent_fraction, 0.99);
    // Measured: 0 clamped points.
    EXPECT_EQ(run.report.clamped_points, 0u);
    // Measured: 45 of 2532 (4 sites), 9 of 2512 (50) and 6 of 2362 (200)
    // collapses fall back to a neighbour that is not nearer the site.
    EXPECT_GE(run.report.collapses_towards_site, 0.97 * run.report.collapses);
  }
}

TEST(BaseMesh, FlatSquareOneBoundaryLoop) {
  const TriangleMesh square = test::flat_square(40);  // 1681 vertices, corner ears included
  for (size_t target : {4, 9, 30, 100}) {
    SCOPED_TRACE(target);
    const VoronoiCells cells = cells_for(square, target);
    const Built run = build_and_check(square, cells);
    // Only boundary vertices are kept beyond the sites: one per boundary run
    // of a cell (measured 4, 8, 18, 39 for 4 .. 100 sites; no interior one).
    EXPECT_EQ(run.report.promoted_vertices, run.report.boundary_vertices_kept);
    EXPECT_LE(run.report.boundary_vertices_kept, boundary_bound(square, cells.cell_of));
    EXPECT_GE(run.report.boundary_vertices_kept, 3u);
    for (size_t b = cells.sites.size(); b < run.base.input_vertex.size(); ++b) {
      const Eigen::Vector3d& p = run.base.mesh.positions[b];
      EXPECT_TRUE(p.x() == 0 || p.x() == 1 || p.y() == 0 || p.y() == 1) << "kept vertex " << b << " is inside";
    }
    // In the plane the flattenings are nearly isometric: images stay close.
    EXPECT_LT(run.measured.max_distance, 0.5 * run.measured.max_base_edge);
    EXPECT_GE(run.measured.adjacent_fraction, 0.99);
  }
}

TEST(BaseMesh, FlatSquareBaseTrianglesFaceUp) {
  // In the plane "no fold" is exact: every base triangle keeps the input's
  // upward orientation, and they cover most of the square (the base boundary
  // is a polygon through kept boundary vertices, inside the square).
  const TriangleMesh square = test::flat_square(12);
  const VoronoiCells cells = cells_for(square, 6);
  const Built run = build_and_check(square, cells);
  double area = 0.0;
  for (const auto& t : run.base.mesh.triangles) {
    const Eigen::Vector3d a = run.base.mesh.positions[t[0]], b = run.base.mesh.positions[t[1]],
                          c = run.base.mesh.positions[t[2]];
    const double z = (b - a).cross(c - a).z();
    EXPECT_GT(z, 0.0) << "a base triangle is flipped";
    area += 0.5 * z;
  }
  EXPECT_GT(area, 0.5);
  EXPECT_LE(area, 1.0 + 1e-12);
}

TEST(BaseMesh, TorusGenusOne) {
  const TriangleMesh ring = torus(48, 16, 2.0, 0.6);  // 768 vertices, Euler 0
  for (size_t target : {30, 80}) {
    SCOPED_TRACE(target);
    const VoronoiCells cells = cells_for(ring, target);
    const Built run = build_and_check(ring, cells);
    // Measured: none promoted at 30 and 80 sites; images within 0.70 and 0.26
    // of their vertex for longest base edges 2.6 and 1.2.
    EXPECT_EQ(run.report.promoted_vertices, 0u);
    EXPECT_GE(run.measured.adjacent_fraction, 0.99);
    EXPECT_LT(run.measured.max_distance, run.measured.max_base_edge);
  }
}

TEST(BaseMesh, EmptyCellOfStillWorks) {
  const TriangleMesh sphere = test::icosphere(3, 1.0);
  const VoronoiCells cells = cells_for(sphere, 40);
  BaseMeshReport report;
  auto base = build_base_mesh(sphere, cells.sites, {}, &report);
  ASSERT_TRUE(base.ok()) << base.status().message();
  EXPECT_TRUE(valid_base_mesh(sphere, cells.sites, base.value(), report, nullptr));
  EXPECT_EQ(report.promoted_vertices, 0u);
}

TEST(BaseMesh, TooFewSitesArePromotedNotFailed) {
  // Three sites cannot span a closed surface: at least one more vertex must
  // stay, and the result is still a valid closed mesh.
  const TriangleMesh sphere = test::icosphere(2, 1.0);
  const VoronoiCells cells = cells_for(sphere, 3);
  const Built run = build_and_check(sphere, cells);
  EXPECT_EQ(run.report.promoted_vertices, 1u);  // a tetrahedron, not two triangles on the same three vertices
  EXPECT_EQ(run.base.mesh.triangles.size(), 4u);
  // A torus needs at least 7 vertices; with 2 sites, some are kept.
  const TriangleMesh ring = torus(24, 8, 2.0, 0.6);
  const Built torus_run = build_and_check(ring, cells_for(ring, 2));
  EXPECT_GE(torus_run.base.mesh.positions.size(), 7u);
}

TEST(BaseMesh, EverySiteMeansNoCollapse) {
  const TriangleMesh cube = test::unit_cube();
  std::vector<int32_t> all(8);
  for (int32_t i = 0; i < 8; ++i) all[i] = 7 - i;
  BaseMeshReport report;
  auto base = build_base_mesh(cube, all, {}, &report);
  ASSERT_TRUE(base.ok()) << base.status().message();
  EXPECT_EQ(report.collapses, 0u);
  EXPECT_EQ(base->mesh.triangles.size(), cube.triangles.size());
  EXPECT_EQ(base->input_vertex, all);
  EXPECT_TRUE(valid_base_mesh(cube, all, base.value(), report, nullptr));
}

TEST(BaseMesh, Deterministic) {
  const TriangleMesh ring = torus(40, 14, 2.0, 0.7);
  const VoronoiCells cells = cells_for(ring, 50);
  auto a = build_base_mesh(ring, cells.sites, cells.cell_of);
  auto b = build_base_mesh(ring, cells.sites, cells.cell_of);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->mesh.triangles, b->mesh.triangles);
  EXPECT_EQ(a->input_vertex, b->input_vertex);
  for (size_t v = 0; v < a->param.size(); ++v) {
    EXPECT_EQ(a->param[v].face, b->param[v].face);
    EXPECT_EQ(a->param[v].bary, b->param[v].bary);
  }
}

TEST(BaseMesh, RejectsBadArguments) {
  const TriangleMesh sphere = test::icosphere(2, 1.0);
  const VoronoiCells cells = cells_for(sphere, 10);

  std::vector<int32_t> repeated = cells.sites;
  repeated[3] = repeated[1];
  auto r = build_base_mesh(sphere, repeated, {});
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("are both vertex"), std::string::npos) << r.status().message();

  std::vector<int32_t> out_of_range = cells.sites;
  out_of_range[2] = static_cast<int32_t>(sphere.positions.size());
  EXPECT_EQ(build_base_mesh(sphere, out_of_range, {}).status().code(), StatusCode::kInvalidArgument);
  out_of_range[2] = -1;
  EXPECT_EQ(build_base_mesh(sphere, out_of_range, {}).status().code(), StatusCode::kInvalidArgument);

  std::vector<int32_t> short_cells(cells.cell_of.begin(), cells.cell_of.end() - 1);
  r = build_base_mesh(sphere, cells.sites, short_cells);
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("cell_of has"), std::string::npos) << r.status().message();

  std::vector<int32_t> bad_label = cells.cell_of;
  bad_label[5] = 10;
  EXPECT_EQ(build_base_mesh(sphere, cells.sites, bad_label).status().code(), StatusCode::kInvalidArgument);
  std::vector<int32_t> site_elsewhere = cells.cell_of;
  site_elsewhere[cells.sites[0]] = 1;
  EXPECT_EQ(build_base_mesh(sphere, cells.sites, site_elsewhere).status().code(), StatusCode::kInvalidArgument);
}

TEST(BaseMesh, RejectsMeshesThatAreNotOneManifoldComponent) {
  const TriangleMesh cube = test::unit_cube();
  const std::vector<int32_t> sites{0, 1, 2, 3};

  TriangleMesh flipped = cube;  // one face turned against its neighbours
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(build_base_mesh(flipped, sites, {}).status().code(), StatusCode::kInvalidMesh);

  TriangleMesh two = cube;  // two cubes
  for (size_t v = 0; v < 8; ++v) two.positions.push_back(cube.positions[v] + Eigen::Vector3d(3, 0, 0));
  for (const auto& t : cube.triangles) two.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
  EXPECT_EQ(build_base_mesh(two, sites, {}).status().code(), StatusCode::kInvalidMesh);

  // Two squares touching at one vertex (a bow tie): vertex 0 has two fans.
  TriangleMesh bowtie;
  bowtie.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {-1, 0, 0}, {-1, -1, 0}};
  bowtie.triangles = {{0, 1, 2}, {0, 3, 4}};
  auto r = build_base_mesh(bowtie, {0}, {});
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidMesh);
  EXPECT_NE(r.status().message().find("not manifold"), std::string::npos) << r.status().message();

  TriangleMesh unused = cube;
  unused.positions.emplace_back(9, 9, 9);
  EXPECT_EQ(build_base_mesh(unused, sites, {}).status().code(), StatusCode::kInvalidMesh);
  EXPECT_EQ(build_base_mesh(TriangleMesh{}, {}, {}).status().code(), StatusCode::kInvalidMesh);
}

// The largest manifold component of a mesh file.
TriangleMesh largest_component(const std::string& path) {
  auto mesh = read_triangle_mesh(path);
  EXPECT_TRUE(mesh.ok()) << mesh.status().message();
  if (!mesh.ok()) return {};
  auto parts = split_into_manifold_components(mesh.value());
  EXPECT_TRUE(parts.ok()) << parts.status().message();
  if (!parts.ok() || parts->empty()) return {};
  std::vector<ComponentMesh>& list = parts.value();
  size_t best = 0;
  for (size_t i = 1; i < list.size(); ++i)
    if (list[i].mesh.positions.size() > list[best].mesh.positions.size()) best = i;
  return std::move(list[best].mesh);
}

TEST(BaseMesh, BundledBunny) {
  const TriangleMesh bunny = largest_component(test::source_path("data/bunny_npm.obj"));
  ASSERT_FALSE(bunny.triangles.empty());
  for (size_t target : {100, 300}) {
    SCOPED_TRACE(target);
    const Built run = build_and_check(bunny, cells_for(bunny, target));
    // Measured: one interior vertex kept at 100 and at 300 sites (a spot
    // where the cells' dual is not a triangulation), none on the boundary.
    EXPECT_LE(run.report.promoted_vertices - run.report.boundary_vertices_kept, 2u);
    EXPECT_GE(run.measured.adjacent_fraction, 0.99);
    EXPECT_LT(run.measured.max_distance, run.measured.max_base_edge);
  }
}

TEST(BaseMesh, CorpusMeshes) {
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not found";
  for (const char* name : {"fandisk.obj", "stanford-bunny.obj"}) {
    SCOPED_TRACE(name);
    const TriangleMesh mesh = largest_component(test::corpus_path(name));
    ASSERT_FALSE(mesh.triangles.empty());
    const VoronoiCells cells = cells_for(mesh, 300);
    const Built run = build_and_check(mesh, cells);
    // Measured: one interior vertex kept on fandisk, none on the bunny, whose
    // 5 holes keep 33 boundary vertices (bound 48).
    EXPECT_LE(run.report.promoted_vertices - run.report.boundary_vertices_kept, 2u);
    EXPECT_LE(run.report.boundary_vertices_kept, boundary_bound(mesh, cells.cell_of));
    EXPECT_GE(run.measured.adjacent_fraction, 0.99);
  }
}

}  // namespace
}  // namespace srcodec
