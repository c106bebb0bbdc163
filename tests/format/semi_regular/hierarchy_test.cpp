#include "format/semi_regular/hierarchy.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdlib>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "tests/test_util.h"

namespace srcodec {
namespace {

using Triangles = std::vector<std::array<int32_t, 3>>;
using Edge = std::pair<int32_t, int32_t>;

int next3(int i) { return (i + 1) % 3; }

struct Base {
  int32_t vertices = 0;
  Triangles triangles;
};

Base base_of(const TriangleMesh& m) { return {static_cast<int32_t>(m.positions.size()), m.triangles}; }

TriangleHierarchy make(const Base& base) {
  auto h = TriangleHierarchy::create(base.vertices, base.triangles);
  EXPECT_TRUE(h.ok()) << h.status().message();
  return std::move(h).value();
}

std::set<Edge> directed_edges(const Triangles& t) {
  std::set<Edge> out;
  for (const auto& f : t)
    for (int c = 0; c < 3; ++c) out.insert({f[c], f[next3(c)]});
  return out;
}

size_t boundary_edge_count(const Triangles& t) {
  const auto d = directed_edges(t);
  return std::count_if(d.begin(), d.end(), [&](const Edge& e) { return !d.count({e.second, e.first}); });
}

size_t undirected_edge_count(const Triangles& t) { return (3 * t.size() + boundary_edge_count(t)) / 2; }

int64_t euler(size_t v, const Triangles& t) {
  return static_cast<int64_t>(v) - static_cast<int64_t>(undirected_edge_count(t)) + static_cast<int64_t>(t.size());
}

// The leaves of the tree truncated at `level`.
std::vector<int32_t> leaves_at(const TriangleHierarchy& h, int32_t level) {
  std::vector<int32_t> out;
  for (size_t i = 0; i < h.nodes().size(); ++i) {
    const auto& n = h.nodes()[i];
    if (n.level <= level && (n.first_child < 0 || n.level == level)) out.push_back(static_cast<int32_t>(i));
  }
  return out;
}

std::vector<int32_t> leaves(const TriangleHierarchy& h) { return leaves_at(h, h.max_level()); }

// `q` in base face `f`: each nonzero weight moves to f's corner at the same
// base vertex; nullopt when q is not on f's closure.
std::optional<Eigen::Vector3d> express_in(const Base& base, const ParamPoint& q, int32_t f) {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (q.bary[i] == 0.0) continue;
    const auto& t = base.triangles[f];
    const auto it = std::find(t.begin(), t.end(), base.triangles[q.face][i]);
    if (it == t.end()) return std::nullopt;
    out[it - t.begin()] += q.bary[i];
  }
  return out;
}

// Everything promised about the mesh of one level, checked from the outside:
// from level_triangles, the public nodes and the vertex records.
class LevelChecker {
 public:
  LevelChecker(const TriangleHierarchy& h, const Base& base) : h_(h), base_(base) {
    // Support of a vertex: the base vertices its nominal place depends on.
    support_.resize(h.vertex_count());
    for (int32_t v = 0; v < h.vertex_count(); ++v) {
      if (v < base.vertices) {
        support_[v] = {v};
        continue;
      }
      const auto pe = h.parent_edge(v);
      std::set<int32_t> s(support_[pe[0]].begin(), support_[pe[0]].end());
      s.insert(support_[pe[1]].begin(), support_[pe[1]].end());
      support_[v].assign(s.begin(), s.end());
    }
    base_edges_ = directed_edges(base.triangles);
    base_euler_ = euler(static_cast<size_t>(base.vertices), base.triangles);
  }

  ::testing::AssertionResult check(int32_t level, size_t* boundary_out = nullptr) const {
    using ::testing::AssertionFailure;
    const Triangles tris = h_.level_triangles(level);
    const int32_t nv = h_.vertex_count();
    std::map<Edge, size_t> directed;
    std::vector<char> used(nv, 0);
    for (size_t i = 0; i < tris.size(); ++i) {
      const auto& t = tris[i];
      for (int c = 0; c < 3; ++c) {
        if (t[c] < 0 || t[c] >= nv) return AssertionFailure() << "level " << level << ": vertex out of range";
        if (h_.vertex_level(t[c]) > level)
          return AssertionFailure() << "level " << level << ": uses vertex " << t[c] << " of level "
                                    << h_.vertex_level(t[c]);
        used[t[c]] = 1;
      }
      if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
        return AssertionFailure() << "level " << level << ": triangle " << i << " repeats a corner";
      for (int c = 0; c < 3; ++c)
        if (!directed.emplace(Edge{t[c], t[next3(c)]}, i).second)
          return AssertionFailure() << "level " << level << ": directed edge (" << t[c] << ", " << t[next3(c)]
                                    << ") used twice";
    }
    size_t boundary = 0, undirected = 0;
    for (const auto& [e, i] : directed) {
      if (directed.count({e.second, e.first})) {
        undirected += e.first < e.second;
        continue;
      }
      ++undirected;
      ++boundary;
      if (!on_base_boundary(e.first, e.second))
        return AssertionFailure() << "level " << level << ": edge (" << e.first << ", " << e.second
                                  << ") has one triangle but is not on the base boundary (a crack)";
    }
    size_t vertices = 0;
    for (int32_t v = 0; v < nv; ++v) {
      if (h_.vertex_level(v) > level) continue;
      if (!used[v]) return AssertionFailure() << "level " << level << ": vertex " << v << " is in no triangle";
      ++vertices;
    }
    if (vertices != h_.level_vertex_count(level))
      return AssertionFailure() << "level " << level << ": " << vertices << " vertices, level_vertex_count says "
                                << h_.level_vertex_count(level);
    const int64_t chi = static_cast<int64_t>(vertices) - static_cast<int64_t>(undirected) +
                        static_cast<int64_t>(tris.size());
    if (chi != base_euler_)
      return AssertionFailure() << "level " << level << ": Euler characteristic " << chi << ", base has " << base_euler_;

    // The tree side: balance and at most one hanging vertex per leaf.
    std::map<Edge, int32_t> midpoint;
    for (int32_t v = base_.vertices; v < nv; ++v)
      if (h_.vertex_level(v) <= level) {
        const auto pe = h_.parent_edge(v);
        midpoint[std::minmax(pe[0], pe[1])] = v;
      }
    const auto& nodes = h_.nodes();
    const std::vector<int32_t> shown = leaves_at(h_, level);
    std::map<Edge, int32_t> node_edge;
    for (int32_t n : shown)
      for (int e = 0; e < 3; ++e) node_edge[{nodes[n].v[e], nodes[n].v[next3(e)]}] = n;
    size_t expected = 0;
    for (int32_t n : shown) {
      const auto& node = nodes[n];
      int hanging = 0;
      for (int e = 0; e < 3; ++e) {
        const int32_t a = node.v[e], b = node.v[next3(e)];
        std::vector<int32_t> across;
        const auto mid = midpoint.find(std::minmax(a, b));
        if (auto it = node_edge.find({b, a}); it != node_edge.end()) {
          across.push_back(it->second);
        } else if (mid != midpoint.end()) {  // finer across: the two halves
          ++hanging;
          for (Edge half : {Edge{b, mid->second}, Edge{mid->second, a}})
            if (auto h2 = node_edge.find(half); h2 != node_edge.end()) across.push_back(h2->second);
          if (across.size() != 2)
            return AssertionFailure() << "level " << level << ": node " << n << " has a hanging vertex "
                                      << mid->second << " but no finer triangles across it";
        } else {  // coarser across: (a, b) is half of the neighbour's edge
          const auto pa = h_.parent_edge(a), pb = h_.parent_edge(b);
          std::vector<Edge> candidates;
          if (pa[0] == b || pa[1] == b) candidates.push_back({b, pa[0] == b ? pa[1] : pa[0]});
          if (pb[0] == a || pb[1] == a) candidates.push_back({pb[0] == a ? pb[1] : pb[0], a});
          for (const Edge& c : candidates)
            if (auto coarse = node_edge.find(c); coarse != node_edge.end()) across.push_back(coarse->second);
        }
        if (across.empty()) {
          if (!on_base_boundary(a, b))
            return AssertionFailure() << "level " << level << ": node " << n << " has no neighbour across edge ("
                                      << a << ", " << b << ")";
        }
        for (int32_t m : across)
          if (std::abs(nodes[m].level - node.level) > 1)
            return AssertionFailure() << "level " << level << ": unbalanced, node " << n << " (level " << node.level
                                      << ") touches node " << m << " (level " << nodes[m].level << ")";
      }
      if (hanging > 1)
        return AssertionFailure() << "level " << level << ": node " << n << " has " << hanging
                                  << " hanging vertices";
      expected += 1 + hanging;
    }
    if (expected != tris.size())
      return AssertionFailure() << "level " << level << ": " << tris.size() << " triangles, expected " << expected
                                << " (leaves plus green halves)";
    if (boundary_out) *boundary_out = boundary;
    return ::testing::AssertionSuccess();
  }

  ::testing::AssertionResult check_all_levels() const {
    for (int32_t level = 0; level <= h_.max_level() + 1; ++level) {
      auto r = check(level);
      if (!r) return r;
    }
    return ::testing::AssertionSuccess();
  }

 private:
  // (a, b) lies on a base edge that has one triangle, in that edge's direction.
  bool on_base_boundary(int32_t a, int32_t b) const {
    std::set<int32_t> s(support_[a].begin(), support_[a].end());
    s.insert(support_[b].begin(), support_[b].end());
    if (s.size() != 2) return false;
    int32_t from = *s.begin(), to = *s.rbegin();
    if (base_edges_.count({to, from}) && !base_edges_.count({from, to})) std::swap(from, to);
    if (!base_edges_.count({from, to}) || base_edges_.count({to, from})) return false;
    return weight(a, to) < weight(b, to);
  }

  double weight(int32_t v, int32_t base_vertex) const {
    const ParamPoint p = h_.nominal_param(v);
    const auto& t = base_.triangles[p.face];
    for (int i = 0; i < 3; ++i)
      if (t[i] == base_vertex) return p.bary[i];
    return 0.0;
  }

  const TriangleHierarchy& h_;
  const Base& base_;
  std::vector<std::vector<int32_t>> support_;
  std::set<Edge> base_edges_;
  int64_t base_euler_ = 0;
};

::testing::AssertionResult check_levels(const TriangleHierarchy& h, const Base& base) {
  return LevelChecker(h, base).check_all_levels();
}

// Vertex records: parents are coarser, nominal places are the parents' mean,
// and every node's corner_bary agrees with its corners' nominal places.
::testing::AssertionResult check_vertex_records(const TriangleHierarchy& h, const Base& base) {
  using ::testing::AssertionFailure;
  for (int32_t v = 0; v < h.vertex_count(); ++v) {
    const ParamPoint p = h.nominal_param(v);
    if (p.face < 0 || p.face >= static_cast<int32_t>(base.triangles.size()))
      return AssertionFailure() << "vertex " << v << ": face " << p.face;
    if (p.bary.minCoeff() < 0.0 || std::abs(p.bary.sum() - 1.0) > 1e-15)
      return AssertionFailure() << "vertex " << v << ": barycentrics " << p.bary.transpose();
    const auto pe = h.parent_edge(v);
    if (v < base.vertices) {
      if (h.vertex_level(v) != 0 || pe[0] != -1 || pe[1] != -1)
        return AssertionFailure() << "base vertex " << v << " has a level or parents";
      const auto& t = base.triangles[p.face];
      if (std::find(t.begin(), t.end(), v) == t.end() || p.bary.maxCoeff() != 1.0 ||
          p.bary[std::find(t.begin(), t.end(), v) - t.begin()] != 1.0)
        return AssertionFailure() << "base vertex " << v << " is not at a corner of its face";
      continue;
    }
    if (h.vertex_level(v) < 1) return AssertionFailure() << "vertex " << v << " of level " << h.vertex_level(v);
    for (int32_t u : pe)
      if (u < 0 || u >= v || h.vertex_level(u) >= h.vertex_level(v))
        return AssertionFailure() << "vertex " << v << " (level " << h.vertex_level(v) << ") has parent " << u;
    const auto a = express_in(base, h.nominal_param(pe[0]), p.face);
    const auto b = express_in(base, h.nominal_param(pe[1]), p.face);
    if (!a || !b) return AssertionFailure() << "vertex " << v << ": a parent is not on base face " << p.face;
    if ((0.5 * (*a + *b) - p.bary).cwiseAbs().maxCoeff() > 1e-15)
      return AssertionFailure() << "vertex " << v << ": nominal " << p.bary.transpose() << ", parents' mean "
                                << (0.5 * (*a + *b)).transpose();
  }
  for (size_t n = 0; n < h.nodes().size(); ++n) {
    const auto& node = h.nodes()[n];
    const auto corners = h.corner_bary(static_cast<int32_t>(n));
    for (int c = 0; c < 3; ++c) {
      const auto q = express_in(base, h.nominal_param(node.v[c]), node.base_face);
      if (!q || (*q - corners[c]).cwiseAbs().maxCoeff() > 1e-15)
        return AssertionFailure() << "node " << n << " corner " << c << ": corner_bary disagrees with vertex "
                                  << node.v[c] << "'s nominal place";
    }
  }
  return ::testing::AssertionSuccess();
}

// Splits every leaf of the finest level, in node order.
void split_level(TriangleHierarchy& h, int32_t level, std::vector<int32_t>* created) {
  const size_t count = h.nodes().size();
  for (size_t i = 0; i < count; ++i)
    if (h.nodes()[i].level == level && h.nodes()[i].first_child < 0) h.split(static_cast<int32_t>(i), created);
}

void check_uniform(const Base& base, int levels) {
  TriangleHierarchy h = make(base);
  const size_t f0 = base.triangles.size();
  const size_t b0 = boundary_edge_count(base.triangles);
  std::vector<std::set<Edge>> level_edges;
  for (int l = 0; l < levels; ++l) {
    const int32_t before = h.vertex_count();
    const Triangles coarse = h.level_triangles(l);
    std::set<Edge> edges;
    for (const auto& t : coarse)
      for (int c = 0; c < 3; ++c) edges.insert(std::minmax(t[c], t[next3(c)]));
    level_edges.push_back(edges);

    std::vector<int32_t> created;
    split_level(h, l, &created);
    ASSERT_EQ(h.max_level(), l + 1);
    // One new vertex per edge of the coarser level, reported in creation order.
    ASSERT_EQ(static_cast<size_t>(h.vertex_count() - before), edges.size());
    ASSERT_EQ(created.size(), edges.size());
    for (size_t i = 0; i < created.size(); ++i) {
      ASSERT_EQ(created[i], before + static_cast<int32_t>(i));
      EXPECT_EQ(h.vertex_level(created[i]), l + 1);
      const auto pe = h.parent_edge(created[i]);
      EXPECT_TRUE(edges.count(std::minmax(pe[0], pe[1]))) << "parent edge is not an edge of level " << l;
    }
    // Parent edges are distinct: each coarse edge is split once.
    std::set<Edge> parents;
    for (int32_t v : created) parents.insert(std::minmax(h.parent_edge(v)[0], h.parent_edge(v)[1]));
    EXPECT_EQ(parents.size(), created.size());
  }
  size_t nodes = 0, per_level = f0;
  for (int l = 0; l <= levels; ++l, per_level *= 4) nodes += per_level;
  EXPECT_EQ(h.nodes().size(), nodes);

  LevelChecker checker(h, base);
  size_t faces = f0, boundary = b0, vertices = static_cast<size_t>(base.vertices);
  for (int32_t l = 0; l <= levels; ++l) {
    size_t b = 0;
    ASSERT_TRUE(checker.check(l, &b));
    const Triangles t = h.level_triangles(l);
    EXPECT_EQ(t.size(), faces) << "level " << l;
    EXPECT_EQ(b, boundary) << "level " << l;
    EXPECT_EQ(h.level_vertex_count(l), vertices) << "level " << l;
    EXPECT_EQ(leaves_at(h, l).size(), faces);
    vertices += undirected_edge_count(t);  // V(l+1) = V(l) + E(l)
    faces *= 4;
    boundary *= 2;
  }
  EXPECT_EQ(h.level_triangles(levels + 3), h.level_triangles(levels)) << "beyond max_level: the finest mesh";
  EXPECT_TRUE(check_vertex_records(h, base));
}

TEST(TriangleHierarchy, UniformTetrahedron) { check_uniform(base_of(test::tetrahedron()), 5); }
TEST(TriangleHierarchy, UniformIcosahedron) { check_uniform(base_of(test::icosphere(0, 1.0)), 5); }
TEST(TriangleHierarchy, UniformFlatSquareHasBoundary) { check_uniform(base_of(test::flat_square(2)), 5); }
TEST(TriangleHierarchy, UniformCube) { check_uniform(base_of(test::unit_cube()), 4); }

TEST(TriangleHierarchy, SingleSplitClosesNeighboursGreen) {
  const Base base = base_of(test::icosphere(0, 1.0));
  TriangleHierarchy h = make(base);
  std::vector<int32_t> created;
  h.split(0, &created);
  EXPECT_EQ(created.size(), 3u);
  EXPECT_EQ(h.nodes().size(), 24u);  // no closure split: each neighbour has one hanging vertex
  EXPECT_EQ(h.max_level(), 1);
  // 19 unsplit + 3 green-bisected neighbours (one extra each) + 4 children.
  EXPECT_EQ(h.level_triangles(1).size(), 19u + 3u + 4u);
  EXPECT_EQ(h.level_triangles(0), base.triangles);
  EXPECT_TRUE(check_levels(h, base));
  // Splitting it again changes nothing.
  h.split(0, &created);
  EXPECT_EQ(created.size(), 3u);
  EXPECT_EQ(h.nodes().size(), 24u);
  // Children order and orientation: (a, m_ab, m_ca), (m_ab, b, m_bc), (m_ca, m_bc, c), (m_ab, m_bc, m_ca).
  const auto& n = h.nodes();
  const int32_t a = n[0].v[0], b = n[0].v[1], c = n[0].v[2];
  const int32_t mab = created[0], mbc = created[1], mca = created[2];
  EXPECT_EQ(h.parent_edge(mab), (std::array<int32_t, 2>{a, b}));
  EXPECT_EQ(h.parent_edge(mbc), (std::array<int32_t, 2>{b, c}));
  EXPECT_EQ(h.parent_edge(mca), (std::array<int32_t, 2>{c, a}));
  const int32_t fc = n[0].first_child;
  EXPECT_EQ(n[fc].v, (std::array<int32_t, 3>{a, mab, mca}));
  EXPECT_EQ(n[fc + 1].v, (std::array<int32_t, 3>{mab, b, mbc}));
  EXPECT_EQ(n[fc + 2].v, (std::array<int32_t, 3>{mca, mbc, c}));
  EXPECT_EQ(n[fc + 3].v, (std::array<int32_t, 3>{mab, mbc, mca}));
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(n[fc + i].parent, 0);
    EXPECT_EQ(n[fc + i].level, 1);
    EXPECT_EQ(n[fc + i].base_face, 0);
  }
  EXPECT_TRUE(check_vertex_records(h, base));
}

TEST(TriangleHierarchy, TwoSplitNeighboursForceClosureSplit) {
  const Base base = base_of(test::icosphere(0, 1.0));
  TriangleHierarchy h = make(base);
  // Face 0 = (0, 11, 5) is adjacent to face 1 (0, 5, 1) across (5, 0) and to
  // face 4 (0, 10, 11) across (0, 11). Splitting faces 1 and 4 leaves face 0
  // with two hanging vertices, so closure must split it too.
  h.split(1);
  EXPECT_LT(h.nodes()[0].first_child, 0);
  h.split(4);
  EXPECT_GE(h.nodes()[0].first_child, 0) << "face 0 had two split neighbours";
  EXPECT_TRUE(check_levels(h, base));
}

TEST(TriangleHierarchy, BalanceSplitsCoarserNeighbourFirst) {
  const Base base = base_of(test::flat_square(1));  // two triangles {0,1,3}, {0,3,2}
  TriangleHierarchy h = make(base);
  h.split(0);
  // Corner child at vertex 3 of face 0 = (0, 1, 3) touches face 1 across the
  // diagonal's half (m, 3): splitting it needs face 1 split first.
  const int32_t child = h.nodes()[0].first_child + 2;
  EXPECT_LT(h.nodes()[1].first_child, 0);
  std::vector<int32_t> created;
  const int32_t before = h.vertex_count();
  h.split(child, &created);
  EXPECT_GE(h.nodes()[1].first_child, 0);
  EXPECT_EQ(h.max_level(), 2);
  // Face 1 created two vertices (the diagonal's midpoint existed), the child three.
  EXPECT_EQ(created.size(), 5u);
  for (size_t i = 0; i < created.size(); ++i) EXPECT_EQ(created[i], before + static_cast<int32_t>(i));
  EXPECT_TRUE(check_levels(h, base));
  EXPECT_TRUE(check_vertex_records(h, base));
}

// Always splits the corner child at one base vertex: 6 levels deep there, the
// rest only as fine as balance and closure demand.
void check_deep_corner(const Base& base, int32_t face, int corner, int levels) {
  TriangleHierarchy h = make(base);
  int32_t node = face;
  for (int l = 0; l < levels; ++l) {
    h.split(node);
    ASSERT_GE(h.nodes()[node].first_child, 0);
    node = h.nodes()[node].first_child + corner;  // corner child i keeps corner i
    ASSERT_EQ(h.nodes()[node].v[corner], base.triangles[face][corner]);
    ASSERT_TRUE(check_levels(h, base)) << "after " << l + 1 << " splits";
  }
  EXPECT_EQ(h.max_level(), levels);
  size_t uniform = 0, per_level = base.triangles.size();
  for (int l = 0; l <= levels; ++l, per_level *= 4) uniform += per_level;
  EXPECT_LT(h.nodes().size() * 4, uniform) << "refinement should stay local";
  EXPECT_TRUE(check_vertex_records(h, base));
}

TEST(TriangleHierarchy, DeepCornerIcosahedron) { check_deep_corner(base_of(test::icosphere(0, 1.0)), 0, 0, 6); }
TEST(TriangleHierarchy, DeepCornerTetrahedron) { check_deep_corner(base_of(test::tetrahedron()), 3, 1, 6); }
TEST(TriangleHierarchy, DeepBoundaryCornerFlatSquare) { check_deep_corner(base_of(test::flat_square(3)), 0, 0, 6); }
TEST(TriangleHierarchy, DeepInteriorCornerFlatSquare) {
  // Vertex 5 is interior in the 3 x 3 grid; face 8 = (5, 6, 10) has it at corner 0.
  const Base base = base_of(test::flat_square(3));
  ASSERT_EQ(base.triangles[8][0], 5);
  check_deep_corner(base, 8, 0, 6);
}

void check_random(const Base& base, uint32_t seed, int splits, int32_t max_level) {
  TriangleHierarchy h = make(base);
  std::mt19937 rng(seed);
  for (int i = 0; i < splits; ++i) {
    // Half the time among the finest leaves, so refinement goes deep in
    // places and balance has long chains to fix, not only shallow splits.
    std::vector<int32_t> candidates;
    const bool deep = rng() % 2;
    int32_t finest = 0;
    for (int32_t n : leaves(h))
      if (h.nodes()[n].level < max_level) finest = std::max(finest, h.nodes()[n].level);
    for (int32_t n : leaves(h))
      if (h.nodes()[n].level < max_level && (!deep || h.nodes()[n].level == finest)) candidates.push_back(n);
    ASSERT_FALSE(candidates.empty());
    const int32_t node = candidates[rng() % candidates.size()];
    const int32_t before = h.vertex_count();
    std::vector<int32_t> created{-7};  // appended to, not replaced
    h.split(node, &created);
    ASSERT_GE(h.nodes()[node].first_child, 0);
    ASSERT_EQ(created.size(), static_cast<size_t>(h.vertex_count() - before) + 1);
    for (size_t k = 1; k < created.size(); ++k) ASSERT_EQ(created[k], before + static_cast<int32_t>(k - 1));
    if (i % 25 == 24) {
      ASSERT_TRUE(check_levels(h, base)) << "after split " << i + 1;
    }
  }
  EXPECT_TRUE(check_levels(h, base));
  EXPECT_TRUE(check_vertex_records(h, base));
  EXPECT_EQ(h.max_level(), max_level) << "the random splits should reach the deepest level allowed";
  // The decoder reserves nodes by this bound (codec/srm_decode.cpp): each
  // split makes 4 nodes and its edges' midpoints, each new vertex the
  // midpoint of at most 2 splits.
  size_t base_faces = 0;
  for (const TriangleHierarchy::Node& n : h.nodes()) base_faces += n.level == 0 ? 1 : 0;
  const size_t new_vertices = static_cast<size_t>(h.vertex_count() - h.base_vertex_count());
  EXPECT_LE(h.nodes().size() - base_faces, 4 * (2 * new_vertices / 3));
}

TEST(TriangleHierarchy, RandomSplitsIcosahedron) { check_random(base_of(test::icosphere(0, 1.0)), 1, 300, 7); }
TEST(TriangleHierarchy, RandomSplitsFlatSquare) { check_random(base_of(test::flat_square(3)), 2, 300, 7); }
TEST(TriangleHierarchy, RandomSplitsCube) { check_random(base_of(test::unit_cube()), 3, 200, 6); }

TEST(TriangleHierarchy, SameSplitsSameResult) {
  const Base base = base_of(test::icosphere(0, 1.0));
  auto run = [&] {
    TriangleHierarchy h = make(base);
    std::mt19937 rng(9);
    for (int i = 0; i < 100; ++i) {
      const auto l = leaves(h);
      h.split(l[rng() % l.size()]);
    }
    return h;
  };
  const TriangleHierarchy a = run(), b = run();
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  for (int32_t l = 0; l <= a.max_level(); ++l) EXPECT_EQ(a.level_triangles(l), b.level_triangles(l));
}

// replayed: every split kept gives the same meshes (vertices renumbered
// through old_vertex); none kept gives the base; one kept gives that split
// and the closure it needs, with its vertices at the old ones' places.
TEST(TriangleHierarchy, ReplayedKeepsTheMarkedSplits) {
  const Base base = base_of(test::icosphere(0, 1.0));
  TriangleHierarchy h = make(base);
  std::mt19937 rng(5);
  for (int i = 0; i < 120; ++i) {
    const auto l = leaves(h);
    h.split(l[rng() % l.size()]);
  }
  auto renumbered = [](Triangles t, const std::vector<int32_t>& old_vertex) {
    for (auto& f : t)
      for (int32_t& v : f) v = old_vertex[v];
    return t;
  };
  std::vector<int32_t> old_vertex, old_node;
  auto all = h.replayed(std::vector<char>(h.nodes().size(), 1), &old_vertex, &old_node);
  ASSERT_TRUE(all.ok()) << all.status().message();
  EXPECT_EQ(all->nodes().size(), h.nodes().size());
  for (int32_t l = 0; l <= h.max_level(); ++l)
    EXPECT_EQ(renumbered(all->level_triangles(l), old_vertex), h.level_triangles(l)) << "level " << l;
  for (size_t n = 0; n < old_node.size(); ++n) EXPECT_EQ(all->nodes()[n].level, h.nodes()[old_node[n]].level);

  auto none = h.replayed(std::vector<char>(h.nodes().size(), 0));
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(none->max_level(), 0);
  EXPECT_EQ(none->level_triangles(0), base.triangles);

  // Keep only the first split node of level 1 and its ancestors.
  int32_t pick = -1;
  for (size_t n = 0; n < h.nodes().size() && pick < 0; ++n)
    if (h.nodes()[n].level == 1 && h.nodes()[n].first_child >= 0) pick = static_cast<int32_t>(n);
  ASSERT_GE(pick, 0);
  std::vector<char> keep(h.nodes().size(), 0);
  keep[pick] = keep[h.nodes()[pick].parent] = 1;
  auto one = h.replayed(keep, &old_vertex, &old_node);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(one->max_level(), 2);
  EXPECT_TRUE(check_levels(one.value(), base));
  EXPECT_TRUE(check_vertex_records(one.value(), base));
  size_t split_at_level_1 = 0;
  for (size_t n = 0; n < one->nodes().size(); ++n) {
    const auto& node = one->nodes()[n];
    Triangles mine{node.v};
    EXPECT_EQ(renumbered(mine, old_vertex)[0], h.nodes()[old_node[n]].v) << "node " << n;
    if (node.level == 1 && node.first_child >= 0) ++split_at_level_1;
  }
  EXPECT_EQ(split_at_level_1, 1u);  // no neighbour of level 1 needed closing by a split
}

// The node locate returns is a leaf of the level, in the point's base face,
// and its corners (by their nominal places) enclose the point.
::testing::AssertionResult located_well(const TriangleHierarchy& h, const Base& base, const ParamPoint& p,
                                        int32_t level) {
  using ::testing::AssertionFailure;
  const int32_t n = h.locate(p, level);
  if (n < 0 || n >= static_cast<int32_t>(h.nodes().size())) return AssertionFailure() << "locate gave " << n;
  const auto& node = h.nodes()[n];
  if (node.level > level || (node.first_child >= 0 && node.level < level))
    return AssertionFailure() << "node " << n << " is not a leaf of level " << level;
  if (node.base_face != p.face) return AssertionFailure() << "node " << n << " is in another base face";
  Eigen::Matrix3d corners;
  for (int c = 0; c < 3; ++c) {
    const auto q = express_in(base, h.nominal_param(node.v[c]), p.face);
    if (!q) return AssertionFailure() << "corner " << node.v[c] << " is not on base face " << p.face;
    corners.col(c) = *q;
  }
  const Eigen::Vector3d local = corners.fullPivLu().solve(p.bary);
  if (local.minCoeff() < -1e-9)
    return AssertionFailure() << "point " << p.bary.transpose() << " lies outside node " << n << " (local "
                              << local.transpose() << ")";
  return ::testing::AssertionSuccess();
}

TEST(TriangleHierarchy, LocateVerticesAndRandomPoints) {
  const Base base = base_of(test::icosphere(0, 1.0));
  TriangleHierarchy h = make(base);
  std::mt19937 rng(5);
  for (int i = 0; i < 200; ++i) {
    std::vector<int32_t> candidates;
    for (int32_t n : leaves(h))
      if (h.nodes()[n].level < 6) candidates.push_back(n);
    h.split(candidates[rng() % candidates.size()]);
  }
  for (int32_t level = 0; level <= h.max_level() + 1; ++level) {
    for (int32_t v = 0; v < h.vertex_count(); ++v)
      ASSERT_TRUE(located_well(h, base, h.nominal_param(v), level)) << "vertex " << v << ", level " << level;
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 500; ++i) {
      ParamPoint p;
      p.face = static_cast<int32_t>(rng() % base.triangles.size());
      p.bary = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
      p.bary /= p.bary.sum();
      ASSERT_TRUE(located_well(h, base, p, level)) << "level " << level;
    }
  }
  // A point in a deep node: the descent stops at the requested level.
  const int32_t deep = leaves(h).back();
  ParamPoint centre;
  centre.face = h.nodes()[deep].base_face;
  const auto c = h.corner_bary(deep);
  centre.bary = (c[0] + c[1] + c[2]) / 3.0;
  EXPECT_EQ(h.locate(centre, h.max_level() + 1), deep);
  int32_t ancestor = deep;
  while (h.nodes()[ancestor].level > 1) ancestor = h.nodes()[ancestor].parent;
  EXPECT_EQ(h.locate(centre, 1), ancestor);
  EXPECT_EQ(h.locate(centre, 0), centre.face);
  ParamPoint bad;
  bad.face = 99;
  EXPECT_EQ(h.locate(bad, 2), -1);
}

TEST(TriangleHierarchy, LocateOnEdgesIsDeterministic) {
  const Base base = base_of(test::tetrahedron());
  TriangleHierarchy h = make(base);
  split_level(h, 0, nullptr);
  split_level(h, 1, nullptr);
  ParamPoint p;
  p.face = 0;
  p.bary = Eigen::Vector3d(0.5, 0.5, 0.0);  // a level-1 midpoint: three children meet there
  const int32_t n = h.locate(p, 1);
  EXPECT_EQ(n, h.nodes()[0].first_child + 3) << "ties go to the middle child";
  EXPECT_TRUE(located_well(h, base, p, 1));
  EXPECT_TRUE(located_well(h, base, p, 2));
}

TEST(TriangleHierarchy, CreateRejectsBadInput) {
  auto expect_error = [](int32_t n, const Triangles& t, StatusCode code, const std::string& words) {
    const auto h = TriangleHierarchy::create(n, t);
    ASSERT_FALSE(h.ok());
    EXPECT_EQ(h.status().code(), code) << h.status().message();
    EXPECT_NE(h.status().message().find(words), std::string::npos) << h.status().message();
  };
  const Triangles tet = test::tetrahedron().triangles;
  expect_error(-1, tet, StatusCode::kInvalidArgument, "base_vertex_count");
  expect_error(0, {}, StatusCode::kInvalidMesh, "no triangles");
  expect_error(3, tet, StatusCode::kInvalidMesh, "outside 0..2");
  expect_error(4, {{0, 1, -1}}, StatusCode::kInvalidMesh, "outside");
  expect_error(3, {{0, 1, 1}}, StatusCode::kInvalidMesh, "repeats a corner");
  expect_error(5, tet, StatusCode::kInvalidMesh, "vertex 4 is used by no triangle");
  // Two triangles with the same directed edge: inconsistent orientation.
  expect_error(4, {{0, 1, 2}, {0, 1, 3}}, StatusCode::kInvalidMesh, "directed edge (0, 1)");
  // Three triangles on one edge: non-manifold.
  expect_error(5, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}, StatusCode::kInvalidMesh, "directed edge (0, 1)");
  // The same triangle twice.
  expect_error(3, {{0, 1, 2}, {1, 2, 0}}, StatusCode::kInvalidMesh, "directed edge");
  // Two triangles glued along all three edges: a sphere, but its level-1
  // mesh would join the midpoints around each valence-2 vertex twice.
  expect_error(3, {{0, 1, 2}, {1, 0, 2}}, StatusCode::kInvalidMesh, "share all three edges");
  expect_error(7, {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}, {4, 5, 6}, {5, 4, 6}}, StatusCode::kInvalidMesh,
               "base triangles 4 and 5");

  const auto ok = TriangleHierarchy::create(4, tet);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok->vertex_count(), 4);
  EXPECT_EQ(ok->base_vertex_count(), 4);
  EXPECT_EQ(ok->max_level(), 0);
  EXPECT_EQ(ok->nodes().size(), 4u);
  EXPECT_EQ(ok->level_vertex_count(0), 4u);
  EXPECT_EQ(ok->level_vertex_count(3), 4u);
}

}  // namespace
}  // namespace srcodec
