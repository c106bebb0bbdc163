// The crease rules of the lifted Butterfly wavelet (wavelet/README.md,
// "Creases"): prediction along and beside creases, the update of crease
// vertices, the plan without creases, bad crease lists.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "format/mesh.h"
#include "tests/test_util.h"
#include "tests/wavelet/hierarchy_helpers.h"
#include "wavelet/butterfly_stencil.h"
#include "wavelet/lifting.h"

namespace srcodec {
namespace {

using Eigen::Vector3d;
using Positions = std::vector<Vector3d>;
using Edge = std::array<int32_t, 2>;
using Edges = std::vector<Edge>;
using test::make_hierarchy;
using test::noisy_base;
using test::place;
using test::refine_random;
using test::predicted_mesh;
using test::PredictedMesh;
using test::refine_uniform;

Edge edge(int32_t a, int32_t b) { return {std::min(a, b), std::max(a, b)}; }

LiftingPlan make_plan(const TriangleHierarchy& h, const Edges& creases) {
  auto plan = LiftingPlan::build(h, h.max_level(), creases);
  EXPECT_TRUE(plan.ok()) << plan.status().message();
  return std::move(plan).value();
}

// The unit cube with each face an n x n grid of squares, each square split
// by the diagonal through the face's centre where n is even (so vertices of
// valence 4, 6 and 8 meet on it), outward triangles.
TriangleMesh grid_cube(int n) {
  TriangleMesh m;
  std::map<std::array<int, 3>, int32_t> ids;
  auto id = [&](const std::array<int, 3>& g) {
    const auto [it, added] = ids.emplace(g, static_cast<int32_t>(m.positions.size()));
    if (added) m.positions.emplace_back(double(g[0]) / n, double(g[1]) / n, double(g[2]) / n);
    return it->second;
  };
  for (int k = 0; k < 3; ++k)
    for (int side = 0; side <= 1; ++side) {
      auto corner = [&](int i, int j) {
        std::array<int, 3> g{};
        g[k] = side * n;
        g[(k + 1) % 3] = i;
        g[(k + 2) % 3] = j;
        return id(g);
      };
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const int32_t a = corner(i, j), b = corner(i + 1, j), c = corner(i + 1, j + 1), d = corner(i, j + 1);
          // (i, j) -> (i + 1, j) -> (i, j + 1) turns around +e_k: outward on side 1.
          const bool through_centre = (i + j) % 2 == 0;
          const std::array<std::array<int32_t, 3>, 2> two =
              through_centre ? std::array<std::array<int32_t, 3>, 2>{{{a, b, c}, {a, c, d}}}
                             : std::array<std::array<int32_t, 3>, 2>{{{a, b, d}, {b, c, d}}};
          for (auto t : two) {
            if (side == 0) std::swap(t[1], t[2]);
            m.triangles.push_back(t);
          }
        }
    }
  return m;
}

// The base edges lying on the cube's 12 edges, sorted.
Edges cube_creases(const TriangleMesh& cube) {
  std::set<Edge> out;
  auto on_edge_line = [&](int32_t a, int32_t b) {
    int fixed = 0;
    for (int k = 0; k < 3; ++k) {
      const double u = cube.positions[a][k], w = cube.positions[b][k];
      fixed += u == w && (u == 0.0 || u == 1.0);
    }
    return fixed >= 2;
  };
  for (const auto& t : cube.triangles)
    for (int c = 0; c < 3; ++c)
      if (on_edge_line(t[c], t[(c + 1) % 3])) out.insert(edge(t[c], t[(c + 1) % 3]));
  return {out.begin(), out.end()};
}

double cube_surface_distance(const Vector3d& p) {
  const Vector3d inside = p.cwiseMax(0.0).cwiseMin(1.0);
  const double outside = (p - inside).norm();
  if (outside > 0.0) return outside;
  return std::min(p.minCoeff(), 1.0 - p.maxCoeff());
}

// The crease edges of the level meshes 0 .. max_level by their definition
// (README, "Creases"), worked out from the vertices' parent edges: a crease
// whose midpoint is a vertex of level j is replaced by its halves at level
// j, any other stays.
std::vector<std::set<Edge>> level_creases(const TriangleHierarchy& h, const Edges& base) {
  std::map<Edge, int32_t> midpoint;
  for (int32_t v = h.base_vertex_count(); v < h.vertex_count(); ++v) {
    const auto [a, b] = h.parent_edge(v);
    midpoint[edge(a, b)] = v;
  }
  std::vector<std::set<Edge>> out{std::set<Edge>(base.begin(), base.end())};
  for (int32_t j = 1; j <= h.max_level(); ++j) {
    std::set<Edge> next;
    for (const Edge& e : out.back()) {
      const auto it = midpoint.find(e);
      if (it != midpoint.end() && h.vertex_level(it->second) == j) {
        next.insert(edge(e[0], it->second));
        next.insert(edge(it->second, e[1]));
      } else {
        next.insert(e);
      }
    }
    out.push_back(std::move(next));
  }
  return out;
}

// Whether some crease of a level mesh is left unsplit by the next level and
// still used by the one after (an adaptive hierarchy's case).
bool has_unsplit_crease(const TriangleHierarchy& h, const std::vector<std::set<Edge>>& creases) {
  for (int32_t j = 1; j < h.max_level(); ++j)
    for (const Edge& e : creases[j - 1])
      if (creases[j].count(e)) return true;
  return false;
}

// One level mesh as the test sees it: directed edges to third corners,
// neighbours, and sharp neighbours (creases and boundary edges).
struct TestLevel {
  std::map<std::pair<int32_t, int32_t>, int32_t> third;
  std::map<int32_t, std::set<int32_t>> ring, sharp;
  std::set<int32_t> crease_vertex;

  TestLevel(const std::vector<std::array<int32_t, 3>>& triangles, const std::set<Edge>& creases) {
    for (const auto& t : triangles)
      for (int c = 0; c < 3; ++c) {
        third[{t[c], t[(c + 1) % 3]}] = t[(c + 2) % 3];
        ring[t[c]].insert(t[(c + 1) % 3]);
        ring[t[(c + 1) % 3]].insert(t[c]);
      }
    for (const auto& [e, c] : third)
      if (!third.count({e.second, e.first})) sharp[e.first].insert(e.second), sharp[e.second].insert(e.first);
    for (const Edge& e : creases) {
      EXPECT_TRUE(third.count({e[0], e[1]}) || third.count({e[1], e[0]})) << "crease not in its level mesh";
      sharp[e[0]].insert(e[1]);
      sharp[e[1]].insert(e[0]);
      crease_vertex.insert(e[0]);
      crease_vertex.insert(e[1]);
    }
  }
  bool is_sharp(int32_t a, int32_t b) const { return sharp.count(a) && sharp.at(a).count(b); }
  bool boundary_vertex(int32_t v) const {  // of the mesh cut along the creases
    if (crease_vertex.count(v)) return true;
    for (int32_t w : ring.at(v))
      if (!third.count({v, w}) || !third.count({w, v})) return true;
    return false;
  }
  // Rule 1: 4-point along the sharp curve, a ghost 2p - q where it ends at p.
  Vector3d curve(int32_t p, int32_t q, const Positions& x) const {
    auto before = [&](int32_t end, int32_t other) -> Vector3d {
      const std::set<int32_t>& s = sharp.at(end);
      if (s.size() != 2) return 2.0 * x[end] - x[other];
      return x[*s.begin() != other ? *s.begin() : *s.rbegin()];
    };
    return 9.0 / 16 * (x[p] + x[q]) - 1.0 / 16 * (before(p, q) + before(q, p));
  }
};

// Checks every odd vertex of levels 1 .. L of `h` whose rule the crease
// rules decide with no fan walk: each crease edge and each boundary edge
// with a crease vertex at an end (rule 1), and each other edge taking the
// 8-point rule on the cut mesh, a wing across a sharp edge reflected (rule
// 2). Level j is predicted from a random base and random details below j.
void expect_crease_rules(const TriangleMesh& base, const TriangleHierarchy& h, const Edges& creases,
                         std::mt19937& rng) {
  const LiftingPlan plan = make_plan(h, creases);
  const std::vector<std::set<Edge>> level = level_creases(h, creases);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  const Positions start = noisy_base(base, 0.05, rng);
  int curves = 0, ends = 0, eight = 0, reflected = 0;
  for (int32_t j = 1; j <= h.max_level(); ++j) {
    Positions detail(h.vertex_count(), Vector3d::Zero());
    for (int32_t v = 0; v < h.vertex_count(); ++v)
      if (h.vertex_level(v) < j) detail[v] = Vector3d(u(rng), u(rng), u(rng));
    const Positions x = inverse_lifting(plan, start, detail, j);
    const TestLevel mesh(h.level_triangles(j - 1), level[j - 1]);
    for (int32_t v = 0; v < h.vertex_count(); ++v) {
      if (h.vertex_level(v) != j) continue;
      const auto [a, b] = h.parent_edge(v);
      const bool crease = level[j - 1].count(edge(a, b)) > 0;
      const bool interior = mesh.third.count({a, b}) && mesh.third.count({b, a});
      if (crease || (!interior && (mesh.crease_vertex.count(a) || mesh.crease_vertex.count(b)))) {
        EXPECT_LT((x[v] - mesh.curve(a, b, x)).norm(), 1e-12) << "level " << j << " vertex " << v;
        ++curves;
        ends += mesh.sharp.at(a).size() != 2 || mesh.sharp.at(b).size() != 2;
        continue;
      }
      if (!interior) continue;
      const size_t va = mesh.ring.at(a).size(), vb = mesh.ring.at(b).size();
      const bool ba = mesh.boundary_vertex(a), bb = mesh.boundary_vertex(b);
      if (!((va == 6 && vb == 6) || (ba && vb == 6) || (bb && va == 6) || (ba && bb))) continue;
      const int32_t l = mesh.third.at({a, b}), r = mesh.third.at({b, a});
      Vector3d expected = 0.5 * (x[a] + x[b]) + (x[l] + x[r]) / 8.0;
      for (const auto& [p, q, w] : {std::array<int32_t, 3>{b, l, a}, {l, a, b}, {a, r, b}, {r, b, a}}) {
        const bool across = !mesh.is_sharp(p, q) && mesh.third.count({q, p});
        expected -= (across ? x[mesh.third.at({q, p})] : Vector3d(x[p] + x[q] - x[w])) / 16.0;
        reflected += !across && mesh.third.count({q, p});  // reflected across a crease
      }
      EXPECT_LT((x[v] - expected).norm(), 1e-12) << "level " << j << " vertex " << v;
      ++eight;
    }
  }
  EXPECT_GT(curves, 20);
  EXPECT_GT(ends, 4);
  EXPECT_GT(eight, 50);
  EXPECT_GT(reflected, 10);
}

// A 6 x 6 grid with a crease across it (boundary to boundary: its ends are
// corners), a one-edge crease inside (two darts) and a two-edge crease from
// inside to the boundary.
struct CreasedSquare {
  TriangleMesh mesh = test::flat_square(6);
  static int32_t id(int i, int j) { return j * 7 + i; }
  Edges creases = [] {
    Edges e;
    for (int i = 0; i < 6; ++i) e.push_back(edge(id(i, 2), id(i + 1, 2)));
    e.push_back(edge(id(3, 4), id(3, 5)));
    e.push_back(edge(id(1, 4), id(1, 5)));
    e.push_back(edge(id(1, 5), id(1, 6)));
    std::sort(e.begin(), e.end());
    return e;
  }();
};

// --- Prediction --------------------------------------------------------------

// The cube with its 12 edges as creases, refined by the prediction alone:
// faces stay flat and inside their squares, edges straight, corners fixed.
// Without the creases it rounds off.
TEST(LiftingCreases, CubeStaysACube) {
  std::mt19937 rng(21);
  for (int n : {1, 2})
    for (bool adaptive : {false, true}) {
      const TriangleMesh cube = grid_cube(n);
      const Edges creases = cube_creases(cube);
      ASSERT_EQ(creases.size(), 12u * n);
      TriangleHierarchy h = make_hierarchy(cube);
      if (adaptive) {
        refine_uniform(h, 1);
        refine_random(h, 5, 120, rng);
      } else {
        refine_uniform(h, 4);
      }
      ASSERT_GE(h.max_level(), 4);
      const std::vector<std::set<Edge>> level = level_creases(h, creases);
      if (adaptive) {
        EXPECT_TRUE(has_unsplit_crease(h, level));
      }
      const Positions zero(h.vertex_count(), Vector3d::Zero());
      const LiftingPlan plan = make_plan(h, creases);
      const Positions x = inverse_lifting(plan, cube.positions, zero, plan.levels());
      double worst = 0.0, worst_edge = 0.0;
      int on_edges = 0;
      for (int32_t v = 0; v < h.vertex_count(); ++v) {
        worst = std::max(worst, cube_surface_distance(x[v]));
        if (v < h.base_vertex_count()) {
          EXPECT_EQ(x[v], cube.positions[v]);
        }
        const int32_t j = h.vertex_level(v);
        if (j == 0 || !level[j - 1].count(edge(h.parent_edge(v)[0], h.parent_edge(v)[1]))) continue;
        // On a cube edge: two coordinates at 0 or 1.
        std::array<double, 3> off{};
        for (int k = 0; k < 3; ++k) off[k] = std::min(std::abs(x[v][k]), std::abs(1.0 - x[v][k]));
        std::sort(off.begin(), off.end());
        worst_edge = std::max(worst_edge, off[1]);
        ++on_edges;
      }
      EXPECT_LT(worst, 1e-12) << "n " << n << (adaptive ? " adaptive" : " uniform");
      EXPECT_LT(worst_edge, 1e-12) << "n " << n << (adaptive ? " adaptive" : " uniform");
      EXPECT_GT(on_edges, 12 * 4);
      const Positions rounded = inverse_lifting(make_plan(h, {}), cube.positions, zero, plan.levels());
      double rounded_worst = 0.0;
      for (const Vector3d& p : rounded) rounded_worst = std::max(rounded_worst, cube_surface_distance(p));
      EXPECT_GT(rounded_worst, 0.01) << "n " << n << (adaptive ? " adaptive" : " uniform");
    }
}

TEST(LiftingCreases, CurveAndCutMeshRules) {
  std::mt19937 rng(22);
  const CreasedSquare square;
  TriangleHierarchy uniform = make_hierarchy(square.mesh);
  refine_uniform(uniform, 3);
  expect_crease_rules(square.mesh, uniform, square.creases, rng);
  TriangleHierarchy adaptive = make_hierarchy(square.mesh);
  refine_uniform(adaptive, 1);
  refine_random(adaptive, 4, 60, rng);
  EXPECT_TRUE(has_unsplit_crease(adaptive, level_creases(adaptive, square.creases)));
  expect_crease_rules(square.mesh, adaptive, square.creases, rng);
  const TriangleMesh cube = grid_cube(2);
  TriangleHierarchy cube_h = make_hierarchy(cube);
  refine_uniform(cube_h, 1);
  refine_random(cube_h, 4, 60, rng);
  expect_crease_rules(cube, cube_h, cube_creases(cube), rng);
}

// Positions made by the crease-aware prediction give zero details and the
// same base under the same plan (and not under the plain one); any positions
// come back from forward then inverse.
void expect_zero_details_and_round_trip(const TriangleMesh& base_mesh, const TriangleHierarchy& h,
                                        const Edges& creases, std::mt19937& rng) {
  const LiftingPlan plan = make_plan(h, creases);
  const Positions base = noisy_base(base_mesh, 0.1, rng);
  const PredictedMesh predicted = predicted_mesh(plan, base);
  EXPECT_LT(predicted.worst_detail, 1e-12);
  EXPECT_LT(predicted.worst_base, 1e-12);
  const Positions& x = predicted.x;
  const double diag = predicted.diagonal;
  const WaveletCoefficients plain = forward_lifting(make_plan(h, {}), x);
  double plain_worst = 0.0;
  for (const Vector3d& d : plain.detail) plain_worst = std::max(plain_worst, d.norm());
  EXPECT_GT(plain_worst, 1e-4 * diag);

  const Positions noisy = place(h, base, 0.05, rng);
  const WaveletCoefficients n = forward_lifting(plan, noisy);
  const Positions back = inverse_lifting(plan, n.base, n.detail, plan.levels());
  double error = 0.0;
  for (int32_t v = 0; v < h.vertex_count(); ++v) error = std::max(error, (back[v] - noisy[v]).norm());
  EXPECT_LT(error, 1e-12 * bounding_box_diagonal(noisy));
}

TEST(LiftingCreases, CreaseSubdividedMeshHasZeroDetails) {
  std::mt19937 rng(23);
  const TriangleMesh cube = grid_cube(2);
  TriangleHierarchy cube_h = make_hierarchy(cube);
  refine_uniform(cube_h, 1);
  refine_random(cube_h, 5, 100, rng);
  ASSERT_TRUE(has_unsplit_crease(cube_h, level_creases(cube_h, cube_creases(cube))));
  expect_zero_details_and_round_trip(cube, cube_h, cube_creases(cube), rng);
  const CreasedSquare square;
  TriangleHierarchy square_h = make_hierarchy(square.mesh);
  refine_uniform(square_h, 1);
  refine_random(square_h, 4, 60, rng);
  ASSERT_TRUE(has_unsplit_crease(square_h, level_creases(square_h, square.creases)));
  expect_zero_details_and_round_trip(square.mesh, square_h, square.creases, rng);
}

// --- Update ------------------------------------------------------------------

// One level over the creased square: with a single detail d on the odd
// vertex of base edge (a, b), forward lifting moves a by u_a d and b by u_b d.
TEST(LiftingCreases, UpdateWeights) {
  const CreasedSquare square;
  TriangleHierarchy h = make_hierarchy(square.mesh);
  refine_uniform(h, 1);
  const LiftingPlan plan = make_plan(h, square.creases);
  std::mt19937 rng(24);
  const Positions base = noisy_base(square.mesh, 0.05, rng);
  const Positions smooth = inverse_lifting(plan, base, Positions(h.vertex_count(), Vector3d::Zero()), 1);
  auto odd_on = [&](int32_t a, int32_t b) {
    for (int32_t v = h.base_vertex_count(); v < h.vertex_count(); ++v)
      if (edge(h.parent_edge(v)[0], h.parent_edge(v)[1]) == edge(a, b)) return v;
    ADD_FAILURE() << "no odd vertex on (" << a << ", " << b << ")";
    return 0;
  };
  auto id = CreasedSquare::id;
  // kPlain: kUpdateWeight / valence, the rule away from creases.
  constexpr double kPlain = -1.0;
  struct Case {
    int32_t a, b;
    double u_a, u_b;
    const char* what;
  };
  const Case cases[] = {
      {id(2, 2), id(3, 2), 0.25, 0.25, "crease edge, both ends on the curve"},
      {id(0, 2), id(1, 2), 0.0, 0.25, "crease edge from a corner on the boundary"},
      {id(3, 4), id(3, 5), 0.0, 0.0, "one-edge crease: two ends"},
      {id(1, 4), id(1, 5), 0.0, 0.25, "crease edge from an end"},
      {id(1, 6), id(0, 6), 0.0, kPlain, "boundary edge from a corner to the square's corner"},
      {id(2, 2), id(2, 3), 0.0, kPlain, "edge off the crease from a crease vertex"},
      {id(4, 4), id(4, 5), kPlain, kPlain, "edge away from the creases"},
      {id(4, 0), id(5, 0), kPlain, kPlain, "boundary edge away from the creases"},
  };
  const TestLevel level0(square.mesh.triangles, {});
  auto weight = [&](double u, int32_t v) {
    return u == kPlain ? kUpdateWeight / static_cast<double>(level0.ring.at(v).size()) : u;
  };
  for (const Case& c : cases) {
    const int32_t v = odd_on(c.a, c.b);
    Positions x = smooth;
    const Vector3d d(0.01, -0.02, 0.03);
    x[v] += d;
    const WaveletCoefficients w = forward_lifting(plan, x);
    EXPECT_LT((w.base[c.a] - (x[c.a] + weight(c.u_a, c.a) * d)).norm(), 1e-15) << c.what;
    EXPECT_LT((w.base[c.b] - (x[c.b] + weight(c.u_b, c.b) * d)).norm(), 1e-15) << c.what;
  }
}

// --- Without creases ---------------------------------------------------------

// No creases: the plan is the plain one, record for record and tap for tap;
// and the crease-aware stencils with no creases are the plain stencils.
TEST(LiftingCreases, NoCreasesIsThePlainPlan) {
  std::mt19937 rng(25);
  std::vector<TriangleHierarchy> hierarchies;
  hierarchies.push_back(make_hierarchy(test::flat_square(4)));
  refine_uniform(hierarchies.back(), 1);
  refine_random(hierarchies.back(), 4, 40, rng);
  hierarchies.push_back(make_hierarchy(test::icosphere(0, 1.0)));
  refine_random(hierarchies.back(), 5, 60, rng);
  hierarchies.push_back(make_hierarchy(grid_cube(2)));
  refine_uniform(hierarchies.back(), 3);
  for (const TriangleHierarchy& h : hierarchies) {
    const LiftingPlan plain = LiftingPlan::build(h, h.max_level()).value();
    const LiftingPlan none = LiftingPlan::build(h, h.max_level(), Edges{}).value();
    ASSERT_EQ(plain.taps().size(), none.taps().size());
    for (size_t i = 0; i < plain.taps().size(); ++i) {
      EXPECT_EQ(plain.taps()[i].vertex, none.taps()[i].vertex);
      EXPECT_EQ(plain.taps()[i].weight, none.taps()[i].weight);
    }
    for (int32_t j = 1; j <= h.max_level(); ++j) {
      ASSERT_EQ(plain.odd_end(j) - plain.odd_begin(j), none.odd_end(j) - none.odd_begin(j));
      auto mesh = LevelMesh::build(h.level_triangles(j - 1), h.vertex_count());
      ASSERT_TRUE(mesh.ok());
      const SharpEdges sharp = SharpEdges::build(mesh.value(), {}).value();
      for (const auto *o = plain.odd_begin(j), *p = none.odd_begin(j); o != plain.odd_end(j); ++o, ++p) {
        EXPECT_TRUE(o->v == p->v && o->a == p->a && o->b == p->b && o->left == p->left && o->right == p->right &&
                    o->wing == p->wing && o->update_divisor_a == p->update_divisor_a &&
                    o->update_divisor_b == p->update_divisor_b)
            << "vertex " << o->v;
        std::vector<LiftingPlan::Tap> without, with;
        butterfly_taps(mesh.value(), o->a, o->b, o->left, o->right, &without);
        butterfly_taps(mesh.value(), sharp, o->a, o->b, o->left, o->right, &with);
        ASSERT_EQ(without.size(), with.size());
        for (size_t i = 0; i < with.size(); ++i) {
          EXPECT_EQ(without[i].vertex, with[i].vertex);
          EXPECT_EQ(without[i].weight, with[i].weight);
        }
        EXPECT_EQ(regular_wings(mesh.value(), o->a, o->b, o->left, o->right),
                  regular_wings(mesh.value(), sharp, o->a, o->b, o->left, o->right));
        EXPECT_EQ(update_divisor(mesh.value(), sharp, o->a, o->b), o->update_divisor_a);
      }
    }
  }
}

// --- Bad input ---------------------------------------------------------------

TEST(LiftingCreases, RefusesBadCreases) {
  const TriangleMesh cube = test::unit_cube();  // edges include (0, 1), (0, 2), (0, 3); not (0, 7)
  TriangleHierarchy h = make_hierarchy(cube);
  refine_uniform(h, 2);
  ASSERT_TRUE(LiftingPlan::build(h, 2, {{0, 1}, {0, 2}}).ok());
  const std::vector<std::pair<Edges, const char*>> bad = {
      {{{0, 7}}, "not an edge of the base mesh"},
      {{{0, 8}}, "below 8"},
      {{{-1, 0}}, "below 8"},
      {{{1, 0}}, "a < b"},
      {{{2, 2}}, "a < b"},
      {{{0, 2}, {0, 1}}, "sorted"},
      {{{0, 1}, {0, 1}}, "no repeats"},
  };
  for (const auto& [creases, message] : bad) {
    const auto plan = LiftingPlan::build(h, 2, creases);
    ASSERT_FALSE(plan.ok()) << message;
    EXPECT_EQ(plan.status().code(), StatusCode::kInvalidArgument) << message;
    EXPECT_NE(plan.status().message().find(message), std::string::npos) << plan.status().message();
  }
  // Refused with no level to build too: the list is checked, not only used.
  EXPECT_FALSE(LiftingPlan::build(h, 0, {{0, 7}}).ok());
}

}  // namespace
}  // namespace srcodec
