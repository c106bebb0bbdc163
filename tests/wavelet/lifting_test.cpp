#include "wavelet/lifting.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
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

namespace srcodec {
namespace {

using Eigen::Vector3d;
using Positions = std::vector<Vector3d>;
using Triangles = std::vector<std::array<int32_t, 3>>;

using test::make_hierarchy;
using test::noisy_base;
using test::place;
using test::refine_random;
using test::refine_uniform;

LiftingPlan make_plan(const TriangleHierarchy& h) {
  auto plan = LiftingPlan::build(h, h.max_level());
  EXPECT_TRUE(plan.ok()) << plan.status().message();
  return std::move(plan).value();
}

double max_distance(const Positions& a, const Positions& b, const TriangleHierarchy& h, int32_t level) {
  double worst = 0.0;
  for (int32_t v = 0; v < h.vertex_count(); ++v)
    if (h.vertex_level(v) <= level) worst = std::max(worst, (a[v] - b[v]).norm());
  return worst;
}

bool all_finite(const Positions& p) {
  return std::all_of(p.begin(), p.end(), [](const Vector3d& v) { return v.allFinite(); });
}

// Forward then full inverse; returns the worst error relative to the diagonal.
double round_trip_error(const TriangleHierarchy& h, const Positions& x) {
  const LiftingPlan plan = make_plan(h);
  const WaveletCoefficients c = forward_lifting(plan, x);
  EXPECT_EQ(c.base.size(), static_cast<size_t>(h.base_vertex_count()));
  EXPECT_EQ(c.detail.size(), static_cast<size_t>(h.vertex_count()));
  const Positions y = inverse_lifting(plan, c.base, c.detail, plan.levels());
  EXPECT_TRUE(all_finite(y));
  return max_distance(x, y, h, h.max_level()) / bounding_box_diagonal(x);
}

TriangleMesh bipyramid(int n, double height, const Vector3d& offset) {
  TriangleMesh m;
  constexpr double kPi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i)
    m.positions.push_back(offset + Vector3d(std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n), 0.0));
  m.positions.push_back(offset + Vector3d(0, 0, height));
  m.positions.push_back(offset + Vector3d(0, 0, -height));
  for (int i = 0; i < n; ++i) {
    m.triangles.push_back({i, (i + 1) % n, n});
    m.triangles.push_back({(i + 1) % n, i, n + 1});
  }
  return m;
}

// Closed components whose vertices have every valence from 3 to 10: a
// tetrahedron (3) and bipyramids over 5- to 10-gons (apexes 5..10, rings 4).
TriangleMesh valence_zoo() {
  TriangleMesh m = test::tetrahedron();
  for (int n = 5; n <= 10; ++n) append_mesh(m, bipyramid(n, 0.5 + 0.1 * n, Vector3d(3.0 * n, 0, 0)));
  return m;
}

std::set<int32_t> valences(const Triangles& tris, int32_t vertex_count) {
  std::vector<std::set<int32_t>> ring(vertex_count);
  for (const auto& t : tris)
    for (int c = 0; c < 3; ++c) {
      ring[t[c]].insert(t[(c + 1) % 3]);
      ring[t[c]].insert(t[(c + 2) % 3]);
    }
  std::set<int32_t> out;
  for (const auto& r : ring) out.insert(static_cast<int32_t>(r.size()));
  return out;
}

// --- 1. Perfect reconstruction ---------------------------------------------

TEST(LiftingRoundTrip, UniformIcosahedron) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  refine_uniform(h, 4);
  ASSERT_EQ(h.max_level(), 4);
  ASSERT_EQ(h.level_triangles(4).size(), 20u * 256u);
  std::mt19937 rng(1);
  const Positions x = place(h, ico.positions, 0.05, rng);
  EXPECT_LT(round_trip_error(h, x), 1e-6);
}

TEST(LiftingRoundTrip, AdaptiveIcosahedronWithGreenClosure) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  std::mt19937 rng(2);
  refine_random(h, 5, 60, rng);
  ASSERT_GE(h.max_level(), 3);
  // Green triangles: some level mesh has more triangles than leaves there.
  bool green = false;
  for (int32_t l = 0; l < h.max_level(); ++l) {
    size_t leaves = 0;
    for (const auto& n : h.nodes()) leaves += n.level <= l && (n.first_child < 0 || n.level == l);
    green |= h.level_triangles(l).size() > leaves;
  }
  ASSERT_TRUE(green);
  const Positions x = place(h, noisy_base(ico, 0.1, rng), 0.05, rng);
  EXPECT_LT(round_trip_error(h, x), 1e-6);
}

TEST(LiftingRoundTrip, OpenPatchWithBoundary) {
  const TriangleMesh patch = test::flat_square(3);
  TriangleHierarchy h = make_hierarchy(patch);
  std::mt19937 rng(3);
  refine_uniform(h, 2);
  refine_random(h, 4, 40, rng);
  const Positions x = place(h, noisy_base(patch, 0.05, rng), 0.02, rng);
  EXPECT_LT(round_trip_error(h, x), 1e-6);
}

TEST(LiftingRoundTrip, BaseValencesThreeToTen) {
  const TriangleMesh zoo = valence_zoo();
  const std::set<int32_t> found = valences(zoo.triangles, static_cast<int32_t>(zoo.positions.size()));
  for (int32_t k = 3; k <= 10; ++k) ASSERT_TRUE(found.count(k)) << "valence " << k;
  TriangleHierarchy h = make_hierarchy(zoo);
  std::mt19937 rng(4);
  refine_uniform(h, 2);
  refine_random(h, 4, 80, rng);
  const Positions x = place(h, noisy_base(zoo, 0.05, rng), 0.05, rng);
  EXPECT_LT(round_trip_error(h, x), 1e-6);
}

// --- 2. Prediction ---------------------------------------------------------

// Positions made by the Butterfly prediction itself (inverse with zero
// details from a random base) must give zero details and the same base.
void expect_zero_details_on_predicted_mesh(const TriangleMesh& base_mesh, TriangleHierarchy& h, std::mt19937& rng) {
  const LiftingPlan plan = make_plan(h);
  const test::PredictedMesh predicted = test::predicted_mesh(plan, noisy_base(base_mesh, 0.1, rng));
  EXPECT_LT(predicted.worst_detail, 1e-9);
  EXPECT_LT(predicted.worst_base, 1e-9);
  const Positions& x = predicted.x;
  const double diag = predicted.diagonal;
  // And a perturbed one does not (the check above can fail).
  Positions moved = x;
  moved.back() += Vector3d(0.01, 0.0, 0.0) * diag;
  const WaveletCoefficients m = forward_lifting(plan, moved);
  EXPECT_GT(m.detail.back().norm(), 1e-3 * diag);
}

TEST(LiftingPredict, ButterflyMeshHasZeroDetails) {
  std::mt19937 rng(5);
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy adaptive = make_hierarchy(ico);
  refine_random(adaptive, 5, 60, rng);
  expect_zero_details_on_predicted_mesh(ico, adaptive, rng);

  const TriangleMesh patch = test::flat_square(4);
  TriangleHierarchy open = make_hierarchy(patch);
  refine_uniform(open, 1);
  refine_random(open, 4, 40, rng);
  expect_zero_details_on_predicted_mesh(patch, open, rng);

  const TriangleMesh zoo = valence_zoo();
  TriangleHierarchy irregular = make_hierarchy(zoo);
  refine_uniform(irregular, 3);
  expect_zero_details_on_predicted_mesh(zoo, irregular, rng);
}

// An independent edge table of one level mesh: third corner of the triangle
// holding a directed edge.
std::map<std::pair<int32_t, int32_t>, int32_t> third_corners(const Triangles& tris) {
  std::map<std::pair<int32_t, int32_t>, int32_t> out;
  for (const auto& t : tris)
    for (int c = 0; c < 3; ++c) out[{t[c], t[(c + 1) % 3]}] = t[(c + 2) % 3];
  return out;
}

// Positions from a random base and random level-1 details, with zero details
// at level 2: level-2 vertices are exactly the predictions from level 1.
Positions predicted_level2(const TriangleHierarchy& h, const TriangleMesh& base, std::mt19937& rng) {
  const LiftingPlan plan = make_plan(h);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  Positions detail(h.vertex_count(), Vector3d::Zero());
  for (int32_t v = 0; v < h.vertex_count(); ++v)
    if (h.vertex_level(v) == 1) detail[v] = Vector3d(u(rng), u(rng), u(rng));
  return inverse_lifting(plan, noisy_base(base, 0.05, rng), detail, 2);
}

TEST(LiftingPredict, RegularInteriorEdgeMatchesEightPointFormula) {
  const TriangleMesh patch = test::flat_square(4);
  TriangleHierarchy h = make_hierarchy(patch);
  refine_uniform(h, 2);
  std::mt19937 rng(6);
  const Positions x = predicted_level2(h, patch, rng);
  const Triangles level1 = h.level_triangles(1);
  const auto third = third_corners(level1);
  std::vector<std::set<int32_t>> ring(h.vertex_count());
  for (const auto& [e, c] : third) ring[e.first].insert(e.second), ring[e.second].insert(e.first);
  auto interior_regular = [&](int32_t v) {
    if (ring[v].size() != 6) return false;
    for (int32_t w : ring[v])
      if (!third.count({v, w}) || !third.count({w, v})) return false;
    return true;
  };
  int checked = 0;
  for (int32_t v = 0; v < h.vertex_count(); ++v) {
    if (h.vertex_level(v) != 2) continue;
    const auto [a, b] = h.parent_edge(v);
    if (!interior_regular(a) || !interior_regular(b)) continue;
    const int32_t c = third.at({a, b}), d = third.at({b, a});
    const int32_t e = third.at({c, b}), f = third.at({a, c}), g = third.at({d, a}), k = third.at({b, d});
    const Vector3d expected =
        0.5 * (x[a] + x[b]) + (x[c] + x[d]) / 8.0 - (x[e] + x[f] + x[g] + x[k]) / 16.0;
    EXPECT_LT((x[v] - expected).norm(), 1e-12) << "vertex " << v;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST(LiftingPredict, BoundaryEdgeMatchesFourPointFormula) {
  const TriangleMesh patch = test::flat_square(4);
  TriangleHierarchy h = make_hierarchy(patch);
  refine_uniform(h, 2);
  std::mt19937 rng(7);
  const Positions x = predicted_level2(h, patch, rng);
  const auto third = third_corners(h.level_triangles(1));
  // Boundary successor / predecessor along the boundary edges (p, q) of level 1.
  std::map<int32_t, int32_t> next, prev;
  for (const auto& [e, c] : third)
    if (!third.count({e.second, e.first})) next[e.first] = e.second, prev[e.second] = e.first;
  int checked = 0;
  for (int32_t v = 0; v < h.vertex_count(); ++v) {
    if (h.vertex_level(v) != 2) continue;
    auto [p, q] = h.parent_edge(v);
    if (!next.count(p) || next[p] != q) std::swap(p, q);
    if (!next.count(p) || next[p] != q) continue;
    const Vector3d expected = 9.0 / 16.0 * (x[p] + x[q]) - (x[prev.at(p)] + x[next.at(q)]) / 16.0;
    EXPECT_LT((x[v] - expected).norm(), 1e-12) << "vertex " << v;
    ++checked;
  }
  EXPECT_EQ(checked, 32);  // the 4 x 4 square has 16 boundary edges at level 0, 32 at level 1
}

TEST(LiftingPredict, ValenceFiveEdgeMatchesExtraordinaryRule) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  refine_uniform(h, 1);
  std::mt19937 rng(8);
  const LiftingPlan plan = make_plan(h);
  const Positions zero(h.vertex_count(), Vector3d::Zero());
  const Positions x = inverse_lifting(plan, noisy_base(ico, 0.1, rng), zero, 1);
  const auto third = third_corners(ico.triangles);
  auto k_rule = [&](int32_t e, int32_t o) {  // Zorin et al. 1996, K = 5
    constexpr double kPi = 3.14159265358979323846;
    Vector3d sum = 0.75 * x[e];
    int32_t w = o;
    for (int i = 0; i < 5; ++i, w = third.at({e, w}))
      sum += (0.25 + std::cos(2 * kPi * i / 5) + 0.5 * std::cos(4 * kPi * i / 5)) / 5 * x[w];
    EXPECT_EQ(w, o);
    return sum;
  };
  for (int32_t v = 12; v < h.vertex_count(); ++v) {
    const auto [a, b] = h.parent_edge(v);
    EXPECT_LT((x[v] - 0.5 * (k_rule(a, b) + k_rule(b, a))).norm(), 1e-12);
  }
}

// --- 3. Partial reconstruction ---------------------------------------------

TEST(LiftingLevels, IntermediateLevelIgnoresFinerDetails) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  std::mt19937 rng(9);
  refine_uniform(h, 1);
  refine_random(h, 4, 50, rng);
  const LiftingPlan plan = make_plan(h);
  const Positions x = place(h, ico.positions, 0.05, rng);
  const WaveletCoefficients c = forward_lifting(plan, x);
  for (int32_t level = 0; level < plan.levels(); ++level) {
    Positions truncated = c.detail, garbage = c.detail;
    for (int32_t v = 0; v < h.vertex_count(); ++v)
      if (h.vertex_level(v) > level) truncated[v] = Vector3d::Zero(), garbage[v] = Vector3d(7, -3, 5);
    const Positions partial = inverse_lifting(plan, c.base, c.detail, level);
    // The full inverse without the finer details gives the same coarse levels.
    const Positions full = inverse_lifting(plan, c.base, truncated, plan.levels());
    EXPECT_LT(max_distance(partial, full, h, level), 1e-12) << "level " << level;
    EXPECT_EQ(partial, inverse_lifting(plan, c.base, garbage, level)) << "level " << level;
    for (int32_t v = 0; v < h.vertex_count(); ++v)
      if (h.vertex_level(v) > level) {
        ASSERT_EQ(partial[v], Vector3d::Zero());
      }
    // Not the finest positions: the update made level <= `level` an approximation.
    EXPECT_GT(max_distance(partial, x, h, level), 1e-6) << "level " << level;
  }
}

// The decoder's staged inverse: levels in several in-place calls, the finer
// slots holding garbage until their level's call, give inverse_lifting's
// bits; with and without the second thread.
TEST(LiftingLevels, InPlaceStepsEqualTheWholeInverse) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  for (bool adaptive : {true, false}) {
    TriangleHierarchy h = make_hierarchy(ico);
    std::mt19937 rng(12);
    if (adaptive) {
      refine_uniform(h, 3);
      refine_random(h, 6, 400, rng);
    } else {
      refine_uniform(h, 6);  // big enough for the second thread on the finest level
    }
    const LiftingPlan plan = make_plan(h);
    ASSERT_TRUE(plan.covers_every_vertex(plan.levels()));
    ASSERT_FALSE(plan.covers_every_vertex(plan.levels() - 1));
    if (!adaptive) {
      ASSERT_GE(plan.odd_end(plan.levels()) - plan.odd_begin(plan.levels()), 16384);
    }
    const Positions x = place(h, noisy_base(ico, 0.1, rng), 0.05, rng);
    const WaveletCoefficients c = forward_lifting(plan, x);
    const Positions whole = inverse_lifting(plan, c.base, c.detail, plan.levels());
    for (bool threads : {false, true}) {
      for (int32_t split = 1; split <= plan.levels(); ++split) {
        Positions staged = c.detail;
        for (int32_t v = 0; v < h.vertex_count(); ++v)
          if (h.vertex_level(v) >= split) staged[v] = Vector3d(7, -3, 5);  // not read yet
        inverse_lifting_in_place(plan, c.base, staged, 1, split - 1, threads);
        for (int32_t v = 0; v < h.vertex_count(); ++v)
          if (h.vertex_level(v) >= split) staged[v] = c.detail[v];
        inverse_lifting_in_place(plan, c.base, staged, split, plan.levels(), threads);
        EXPECT_TRUE(staged == whole) << (adaptive ? "adaptive" : "uniform") << ", split at " << split
                                     << (threads ? ", threads" : "");
      }
    }
  }
}

// --- 4. Frames ---------------------------------------------------------------

TEST(LiftingFrames, SphereDetailsAreMostlyNormal) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  refine_uniform(h, 5);
  const LiftingPlan plan = make_plan(h);
  // Subdivide and project: each level is the Butterfly prediction from the
  // coarser one, pushed back to the unit sphere. (Normalized edge midpoints,
  // the usual icosphere, would not do: that sampling drifts tangentially
  // away from any smooth prediction, by as much as its normal offset.)
  Positions x(h.vertex_count(), Vector3d::Zero());
  std::copy(ico.positions.begin(), ico.positions.end(), x.begin());
  for (int32_t j = 1; j <= plan.levels(); ++j)
    for (const auto* o = plan.odd_begin(j); o != plan.odd_end(j); ++o) {
      Vector3d p = Vector3d::Zero();
      for (const LiftingPlan::Tap& t : plan.stencil(*o)) p += t.weight * x[t.vertex];
      x[o->v] = p.normalized();
    }
  const WaveletCoefficients c = forward_lifting(plan, x);
  double normal = 0.0, tangent = 0.0;
  for (int32_t v = 12; v < h.vertex_count(); ++v) {
    normal += std::abs(c.detail[v].x());
    tangent += c.detail[v].tail<2>().norm();
  }
  ASSERT_GT(normal, 0.0);
  EXPECT_LT(tangent / normal, 0.05) << "normal " << normal << " tangential " << tangent;
}

// One coefficient moves its vertex along the frame's axes: x along the
// outward normal, y along the parent edge a -> b, z along n x y.
TEST(LiftingFrames, AxesPointOutwardAndAlongTheParentEdge) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  refine_uniform(h, 2);
  const LiftingPlan plan = make_plan(h);
  const Positions zero(h.vertex_count(), Vector3d::Zero());
  const Positions smooth = inverse_lifting(plan, ico.positions, zero, 2);
  for (int32_t v : {12, 20, 41, 100, 150}) {
    const auto [a, b] = h.parent_edge(v);
    // The two triangles (a, b, l) and (b, a, r) of the coarser level.
    const auto third = third_corners(h.level_triangles(h.vertex_level(v) - 1));
    const int32_t l = third.at({a, b}), r = third.at({b, a});
    const Vector3d e = smooth[b] - smooth[a];
    const Vector3d normal = (e.cross(smooth[l] - smooth[a]) - e.cross(smooth[r] - smooth[b])).normalized();
    EXPECT_GT(normal.dot((smooth[a] + smooth[b]).normalized()), 0.99);  // outward
    const Vector3d along = (e - e.dot(normal) * normal).normalized();
    const Vector3d axes[3] = {normal, along, normal.cross(along)};
    for (int k = 0; k < 3; ++k) {
      Positions detail = zero;
      detail[v][k] = 0.01;
      const Positions moved = inverse_lifting(plan, ico.positions, detail, 2);
      // Parallel to the axis (the undone update shrinks it a little, along the same direction).
      const Vector3d shift = moved[v] - smooth[v];
      EXPECT_GT(shift.norm(), 0.005);
      EXPECT_GT(shift.normalized().dot(axes[k]), 1.0 - 1e-9) << "vertex " << v << " axis " << k;
    }
  }
}

// --- 5. Degenerate input, determinism ----------------------------------------

TEST(LiftingRobustness, DegenerateInputsGiveNoNaN) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  std::mt19937 rng(10);
  refine_uniform(h, 1);
  refine_random(h, 4, 40, rng);
  const LiftingPlan plan = make_plan(h);
  const Positions same(h.vertex_count(), Vector3d(1, 2, 3));
  const WaveletCoefficients c = forward_lifting(plan, same);
  EXPECT_TRUE(all_finite(c.detail));
  // Stencil weights sum to 1 up to rounding: constants give zero details.
  for (const auto& d : c.detail) EXPECT_LT(d.norm(), 1e-12);
  for (const auto& b : c.base) EXPECT_LT((b - Vector3d(1, 2, 3)).norm(), 1e-12);
  EXPECT_LT(max_distance(inverse_lifting(plan, c.base, c.detail, plan.levels()), same, h, h.max_level()), 1e-12);
  // Degenerate coarse levels (all base vertices equal, collinear, or not)
  // with noisy finer vertices: frames must stay orthonormal.
  for (const Positions& base : {Positions(12, Vector3d(1, 2, 3)), [] {
         Positions p(12);
         for (int i = 0; i < 12; ++i) p[i] = Vector3d(i, 2 * i, -i);
         return p;
       }()}) {
    const Positions x = place(h, base, 0.01, rng);
    const WaveletCoefficients d = forward_lifting(plan, x);
    ASSERT_TRUE(all_finite(d.detail));
    const Positions y = inverse_lifting(plan, d.base, d.detail, plan.levels());
    ASSERT_TRUE(all_finite(y));
    EXPECT_LT(max_distance(x, y, h, h.max_level()), 1e-9);
  }
}

TEST(LiftingRobustness, DeterministicAcrossRebuilds) {
  std::mt19937 rng_a(11), rng_b(11), noise(12);
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy ha = make_hierarchy(ico), hb = make_hierarchy(ico);
  refine_random(ha, 4, 50, rng_a);
  refine_random(hb, 4, 50, rng_b);
  const LiftingPlan pa = make_plan(ha), pb = make_plan(hb);
  ASSERT_EQ(pa.taps().size(), pb.taps().size());
  const Positions x = place(ha, ico.positions, 0.05, noise);
  const WaveletCoefficients ca = forward_lifting(pa, x), cb = forward_lifting(pb, x);
  EXPECT_EQ(ca.base, cb.base);
  EXPECT_EQ(ca.detail, cb.detail);
  EXPECT_EQ(inverse_lifting(pa, ca.base, ca.detail, 4), inverse_lifting(pb, cb.base, cb.detail, 4));
}

// The plan keeps no taps for a regular odd vertex, only its four wings: its
// stencil must be the one butterfly_taps computes there, term for term once
// repeated vertices are summed; every other odd keeps butterfly_taps' taps.
void expect_plan_stencils_are_butterfly_taps(const TriangleHierarchy& h, double min_regular_share) {
  const LiftingPlan plan = make_plan(h);
  size_t odds = 0, regular = 0;
  for (int32_t j = 1; j <= plan.levels(); ++j) {
    auto mesh = LevelMesh::build(h.level_triangles(j - 1), h.vertex_count());
    ASSERT_TRUE(mesh.ok()) << mesh.status().message();
    for (const auto* o = plan.odd_begin(j); o != plan.odd_end(j); ++o) {
      std::vector<LiftingPlan::Tap> expected;
      butterfly_taps(mesh.value(), o->a, o->b, o->left, o->right, &expected);
      std::map<int32_t, double> got;
      for (const LiftingPlan::Tap& t : plan.stencil(*o)) got[t.vertex] += t.weight;
      ASSERT_EQ(got.size(), expected.size()) << "vertex " << o->v;
      for (const LiftingPlan::Tap& t : expected) EXPECT_NEAR(got[t.vertex], t.weight, 1e-15) << "vertex " << o->v;
      ++odds;
      regular += o->regular();
    }
  }
  EXPECT_GE(static_cast<double>(regular), min_regular_share * static_cast<double>(odds))
      << regular << " regular of " << odds;
  EXPECT_LT(regular, odds);  // both kinds were checked
}

TEST(LiftingPlan, RegularOddsHaveTheButterflyStencil) {
  std::mt19937 rng(14);
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy uniform = make_hierarchy(ico);
  refine_uniform(uniform, 4);
  expect_plan_stencils_are_butterfly_taps(uniform, 0.75);
  TriangleHierarchy adaptive = make_hierarchy(ico);
  refine_random(adaptive, 5, 80, rng);
  expect_plan_stencils_are_butterfly_taps(adaptive, 0.1);
  // Boundary edges: the 8-point rule with a reflected wing is not regular.
  TriangleHierarchy open = make_hierarchy(test::flat_square(4));
  refine_uniform(open, 3);
  expect_plan_stencils_are_butterfly_taps(open, 0.5);
  TriangleHierarchy zoo = make_hierarchy(valence_zoo());
  refine_uniform(zoo, 3);
  expect_plan_stencils_are_butterfly_taps(zoo, 0.3);
}

TEST(LiftingPlan, RejectsNegativeLevelsAndAcceptsExtraLevels) {
  const TriangleMesh ico = test::icosphere(0, 1.0);
  TriangleHierarchy h = make_hierarchy(ico);
  refine_uniform(h, 2);
  EXPECT_FALSE(LiftingPlan::build(h, -1).ok());
  auto deep = LiftingPlan::build(h, 7);
  ASSERT_TRUE(deep.ok());
  EXPECT_EQ(deep->levels(), 7);
  std::mt19937 rng(13);
  const Positions x = place(h, ico.positions, 0.05, rng);
  const WaveletCoefficients c = forward_lifting(deep.value(), x);
  EXPECT_LT(max_distance(inverse_lifting(deep.value(), c.base, c.detail, 7), x, h, 2), 1e-12);
  // Stencil weights sum to one (affine invariance).
  for (int32_t j = 1; j <= 2; ++j)
    for (const auto* o = deep->odd_begin(j); o != deep->odd_end(j); ++o) {
      double sum = 0.0;
      for (const LiftingPlan::Tap& t : deep->stencil(*o)) sum += t.weight;
      EXPECT_NEAR(sum, 1.0, 1e-12);
    }
}

}  // namespace
}  // namespace srcodec
