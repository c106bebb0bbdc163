// Balanced red-green 1-to-4 refinement (Kammoun, Payan, Antonini §III-B; the
// red-green rules are those of Bank, Sherman, Weiser 1983 and of adaptive
// multiresolution meshes such as Zorin, Schröder, Sweldens 1997).
//
// Why neighbour links and not edge hash maps: the children of a split node
// sit in a fixed pattern (edge e of a node is halved into edge e of corner
// child e and edge e of corner child e + 1; the inner edges all face the
// middle child), so the same-level neighbour across any child edge is either
// a sibling or a child of the parent's same-level neighbour, and a shared
// midpoint is a corner of that neighbour's children. Three int32 per node thus
// answer every question the directed-edge and midpoint maps would (neighbour,
// coarser neighbour, shared midpoint, base boundary) in O(1) without hashing,
// in 12 bytes per node instead of ~100 for three hash entries, and nothing
// depends on hash iteration order.
//
// Invariants kept by split():
//  - Balance: a node is split only when every edge of it that is not on the
//    base boundary has a same-level neighbour; so adjacent_ of a split node is
//    -1 only on the base boundary, and a leaf's coarser neighbour across edge
//    e is its parent's same-level neighbour across the parent's edge e.
//  - Closure: no leaf has two or more split same-level neighbours, so every
//    leaf of every level mesh has at most one hanging vertex, of the next level.
#include "format/semi_regular/hierarchy.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <string>
#include <utility>

namespace srcodec {
namespace {

constexpr int next3(int i) { return i == 2 ? 0 : i + 1; }

uint64_t edge_key(int32_t a, int32_t b) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

std::string edge_name(int32_t a, int32_t b) { return "(" + std::to_string(a) + ", " + std::to_string(b) + ")"; }

// Row j: the barycentrics of child corner j in terms of its parent's corners.
// Corner child i keeps corner i and puts the midpoint of (i, j) at position j;
// the middle child is (m01, m12, m20).
Eigen::Matrix3d child_map(int32_t child) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  if (child < 3) {
    for (int j = 0; j < 3; ++j) {
      m(j, child) += j == child ? 1.0 : 0.5;
      if (j != child) m(j, j) += 0.5;
    }
  } else {
    for (int j = 0; j < 3; ++j) m(j, j) = m(j, next3(j)) = 0.5;
  }
  return m;
}

}  // namespace

StatusOr<TriangleHierarchy> TriangleHierarchy::create(int32_t base_vertex_count,
                                                      const std::vector<std::array<int32_t, 3>>& base_triangles) {
  const std::string where = "TriangleHierarchy: ";
  if (base_vertex_count < 0)
    return invalid_argument(where + "base_vertex_count is " + std::to_string(base_vertex_count) + "; use 0 or more");
  if (base_triangles.empty()) return invalid_mesh(where + "the base mesh has no triangles");
  // Every split adds 4 nodes; keep a margin so node ids stay in int32.
  if (base_triangles.size() > static_cast<size_t>(std::numeric_limits<int32_t>::max() / 8))
    return invalid_mesh(where + std::to_string(base_triangles.size()) + " base triangles exceed the 32-bit index range");
  const int32_t face_count = static_cast<int32_t>(base_triangles.size());

  std::vector<int32_t> first_face(base_vertex_count, -1);
  for (int32_t f = 0; f < face_count; ++f) {
    const auto& t = base_triangles[f];
    for (int c = 0; c < 3; ++c)
      if (t[c] < 0 || t[c] >= base_vertex_count)
        return invalid_mesh(where + "base triangle " + std::to_string(f) + " uses vertex " + std::to_string(t[c]) +
                            ", outside 0.." + std::to_string(base_vertex_count - 1));
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
      return invalid_mesh(where + "base triangle " + std::to_string(f) + " repeats a corner (" +
                          std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")");
    for (int32_t v : t)
      if (first_face[v] < 0) first_face[v] = f;
  }
  for (int32_t v = 0; v < base_vertex_count; ++v)
    if (first_face[v] < 0)
      return invalid_mesh(where + "base vertex " + std::to_string(v) +
                          " is used by no triangle; drop unreferenced vertices first");

  // Directed edges sorted by (from, to): duplicates are adjacent, twins found
  // by binary search. Half-edge h = 3 f + e runs from corner e to corner e + 1.
  std::vector<std::pair<uint64_t, int32_t>> edges(3 * base_triangles.size());
  for (int32_t f = 0; f < face_count; ++f)
    for (int e = 0; e < 3; ++e)
      edges[3 * f + e] = {edge_key(base_triangles[f][e], base_triangles[f][next3(e)]), 3 * f + e};
  std::sort(edges.begin(), edges.end());
  for (size_t i = 1; i < edges.size(); ++i)
    if (edges[i].first == edges[i - 1].first) {
      const int32_t h = edges[i].second;
      const auto& t = base_triangles[h / 3];
      return invalid_mesh(where + "directed edge " + edge_name(t[h % 3], t[next3(h % 3)]) +
                          " is used by base triangles " + std::to_string(edges[i - 1].second / 3) + " and " +
                          std::to_string(h / 3) +
                          ": the base mesh is non-manifold or inconsistently oriented there");
    }

  TriangleHierarchy h;
  h.base_vertex_count_ = base_vertex_count;
  h.nodes_.resize(face_count);
  h.adjacent_.assign(face_count, {-1, -1, -1});
  for (int32_t f = 0; f < face_count; ++f) {
    Node& node = h.nodes_[f];
    node.v = base_triangles[f];
    node.base_face = f;
    for (int e = 0; e < 3; ++e) {
      const uint64_t twin = edge_key(node.v[next3(e)], node.v[e]);
      const auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(twin, int32_t{-1}));
      if (it != edges.end() && it->first == twin) h.adjacent_[f][e] = it->second / 3;
    }
    // Two triangles sharing two edges share all three (same corners, opposite
    // orientation): a closed two-triangle component. Its level-1 mesh would
    // join the same two midpoints by two different edges (the corner children
    // at either valence-2 vertex), which no triangle list can tell apart.
    const auto& across = h.adjacent_[f];
    if (across[0] >= 0 && (across[0] == across[1] || across[0] == across[2]))
      return invalid_mesh(where + "base triangles " + std::to_string(f) + " and " + std::to_string(across[0]) +
                          " share all three edges (a closed two-triangle component); its refinement would join "
                          "two vertices by two edges");
    if (across[1] >= 0 && across[1] == across[2])
      return invalid_mesh(where + "base triangles " + std::to_string(f) + " and " + std::to_string(across[1]) +
                          " share all three edges (a closed two-triangle component); its refinement would join "
                          "two vertices by two edges");
  }
  h.vertex_level_.assign(base_vertex_count, 0);
  h.parent_edge_.assign(base_vertex_count, {-1, -1});
  h.vertex_origin_.resize(base_vertex_count);
  for (int32_t v = 0; v < base_vertex_count; ++v) {
    const auto& t = base_triangles[first_face[v]];
    h.vertex_origin_[v] = 3 * first_face[v] + static_cast<int32_t>(std::find(t.begin(), t.end(), v) - t.begin());
  }
  h.vertices_at_level_ = {static_cast<size_t>(base_vertex_count)};
  h.base_face_count_ = static_cast<size_t>(face_count);
  return h;
}

ParamPoint TriangleHierarchy::nominal_param(int32_t v) const {
  assert(v >= 0 && v < vertex_count());
  const int32_t node = vertex_origin_[v] / 3, e = vertex_origin_[v] % 3;
  ParamPoint p;
  p.face = nodes_[node].base_face;
  if (v < base_vertex_count_) {
    p.bary = Eigen::Vector3d::Zero();
    p.bary[e] = 1.0;
    return p;
  }
  const std::array<Eigen::Vector3d, 3> corners = corner_bary(node);
  p.bary = 0.5 * (corners[e] + corners[next3(e)]);
  return p;
}

void TriangleHierarchy::reserve(size_t nodes, size_t vertices) {
  nodes_.reserve(nodes);
  adjacent_.reserve(nodes);
  vertex_level_.reserve(vertices);
  parent_edge_.reserve(vertices);
  vertex_origin_.reserve(vertices);
}

std::vector<MemoryRange> TriangleHierarchy::reserved_memory() const {
  return {capacity_of(nodes_), capacity_of(adjacent_), capacity_of(vertex_level_), capacity_of(parent_edge_),
          capacity_of(vertex_origin_)};
}

size_t TriangleHierarchy::level_vertex_count(int32_t level) const {
  size_t count = 0;
  for (int32_t l = 0; l <= level && l < static_cast<int32_t>(vertices_at_level_.size()); ++l)
    count += vertices_at_level_[l];
  return count;
}

std::array<Eigen::Vector3d, 3> TriangleHierarchy::corner_bary(int32_t node) const {
  assert(node >= 0 && node < static_cast<int32_t>(nodes_.size()));
  // Compose the child maps bottom-up: rows of `map` are the node's corners in
  // terms of the current ancestor's corners; at the root, of the base face's.
  Eigen::Matrix3d map = Eigen::Matrix3d::Identity();
  for (int32_t t = node; nodes_[t].parent >= 0; t = nodes_[t].parent)
    map = map * child_map(t - nodes_[nodes_[t].parent].first_child);
  return {map.row(0).transpose(), map.row(1).transpose(), map.row(2).transpose()};
}

int32_t TriangleHierarchy::edge_index(int32_t node, int32_t a, int32_t b) const {
  const auto& v = nodes_[node].v;
  for (int e = 0; e < 3; ++e)
    if (v[e] == a && v[next3(e)] == b) return e;
  assert(false && "edge_index: the neighbour does not have the twin edge");
  return -1;
}

// The coarser leaf that must be split before `node` can be (balance), or -1
// when every edge of `node` has a same-level neighbour or lies on the base
// boundary.
int32_t TriangleHierarchy::coarser_leaf_across(int32_t node) const {
  const Node& n = nodes_[node];
  if (n.parent < 0) return -1;  // base edges without a twin are base boundary
  for (int e = 0; e < 3; ++e) {
    if (adjacent_[node][e] >= 0) continue;
    // Inner edges always have their sibling, so edge e is outer: it lies in
    // the parent's edge e. The parent was split balanced, so the parent has a
    // same-level neighbour there unless that edge is base boundary; that
    // neighbour is a leaf, else its child would be linked to `node`.
    const int32_t across = adjacent_[n.parent][e];
    if (across >= 0) {
      assert(nodes_[across].first_child < 0);
      return across;
    }
  }
  return -1;
}

int32_t TriangleHierarchy::split_neighbour_count(int32_t node) const {
  int32_t count = 0;
  for (int32_t across : adjacent_[node])
    if (across >= 0 && nodes_[across].first_child >= 0) ++count;
  return count;
}

StatusOr<TriangleHierarchy> TriangleHierarchy::replayed(const std::vector<char>& keep, std::vector<int32_t>* old_vertex,
                                                        std::vector<int32_t>* old_node_out) const {
  std::vector<std::array<int32_t, 3>> base(base_face_count_);
  for (size_t f = 0; f < base_face_count_; ++f) base[f] = nodes_[f].v;  // the roots, in base face order
  SRCODEC_ASSIGN_OR_RETURN(TriangleHierarchy out, create(base_vertex_count_, base));
  // Per node of `out`, the node at the same place here: the roots for
  // themselves, children for the children in the same order (a parent comes
  // before its children).
  std::vector<int32_t> old_node;
  auto match = [&] {
    old_node.resize(out.nodes_.size());
    for (size_t n = 0; n < out.nodes_.size(); ++n) {
      if (n < base_face_count_) old_node[n] = static_cast<int32_t>(n);
      const int32_t child = out.nodes_[n].first_child;
      if (child < 0) continue;
      // out's splits are a subset of these, or their balance and closure,
      // which this hierarchy (balanced and closed) has as well
      assert(nodes_[old_node[n]].first_child >= 0);
      for (int c = 0; c < 4; ++c) old_node[child + c] = nodes_[old_node[n]].first_child + c;
    }
  };
  for (int32_t level = 0; level < max_level_; ++level) {
    match();
    std::vector<int32_t> new_node(nodes_.size(), -1);
    for (size_t n = 0; n < old_node.size(); ++n) new_node[old_node[n]] = static_cast<int32_t>(n);
    for (size_t o = 0; o < nodes_.size(); ++o)  // in this hierarchy's order, as the splits were made
      if (nodes_[o].level == level && nodes_[o].first_child >= 0 && o < keep.size() && keep[o] && new_node[o] >= 0)
        out.split(new_node[o]);
  }
  match();
  if (old_vertex) {
    old_vertex->assign(static_cast<size_t>(out.vertex_count()), -1);
    for (size_t n = 0; n < out.nodes_.size(); ++n)
      for (int c = 0; c < 3; ++c) (*old_vertex)[out.nodes_[n].v[c]] = nodes_[old_node[n]].v[c];
  }
  if (old_node_out) *old_node_out = std::move(old_node);
  return out;
}

void TriangleHierarchy::split(int32_t node, std::vector<int32_t>* new_vertices) {
  assert(node >= 0 && node < static_cast<int32_t>(nodes_.size()));
  if (node < 0 || node >= static_cast<int32_t>(nodes_.size()) || nodes_[node].first_child >= 0) return;
  // A stack rather than recursion: balance chains are as long as the level,
  // but closure can ripple across a whole region.
  std::vector<int32_t>& pending = pending_;
  pending.assign(1, node);
  while (!pending.empty()) {
    const int32_t t = pending.back();
    if (nodes_[t].first_child >= 0) {
      pending.pop_back();
      continue;
    }
    const int32_t coarser = coarser_leaf_across(t);
    if (coarser >= 0) {
      pending.push_back(coarser);  // split it first, then come back to t
      continue;
    }
    pending.pop_back();
    split_balanced(t, new_vertices);
    for (int32_t across : adjacent_[t])
      if (across >= 0 && nodes_[across].first_child < 0 && split_neighbour_count(across) >= 2)
        pending.push_back(across);
  }
}

// The red split of a leaf whose every non-boundary edge has a same-level
// neighbour.
void TriangleHierarchy::split_balanced(int32_t node, std::vector<int32_t>* new_vertices) {
  const Node n = nodes_[node];  // a copy: nodes_ grows below
  const int32_t level = n.level + 1;
  const int32_t first = static_cast<int32_t>(nodes_.size());

  std::array<int32_t, 3> mid{};
  for (int e = 0; e < 3; ++e) {
    const int32_t across = adjacent_[node][e];
    if (across >= 0 && nodes_[across].first_child >= 0) {
      // The neighbour's corner child f holds the midpoint of its edge f.
      const int32_t f = edge_index(across, n.v[next3(e)], n.v[e]);
      mid[e] = nodes_[nodes_[across].first_child + f].v[next3(f)];
      continue;
    }
    mid[e] = vertex_count();
    vertex_level_.push_back(level);
    // Fields written in place, here and below: a braced temporary is built on
    // the stack with 4-byte stores and copied with one wider load, which the
    // CPU cannot forward from them (a stall of a dozen cycles per element,
    // most of this function's time in the decoder's replay).
    parent_edge_.emplace_back();
    parent_edge_.back()[0] = n.v[e];
    parent_edge_.back()[1] = n.v[next3(e)];
    vertex_origin_.push_back(3 * node + e);
    if (static_cast<int32_t>(vertices_at_level_.size()) <= level) vertices_at_level_.resize(level + 1, 0);
    ++vertices_at_level_[level];
    if (new_vertices) new_vertices->push_back(mid[e]);
  }

  const std::array<std::array<int32_t, 3>, 4> corners_of = {{{n.v[0], mid[0], mid[2]},
                                                            {mid[0], n.v[1], mid[1]},
                                                            {mid[2], mid[1], n.v[2]},
                                                            {mid[0], mid[1], mid[2]}}};
  for (int c = 0; c < 4; ++c) {
    Node& child = nodes_.emplace_back();
    for (int k = 0; k < 3; ++k) child.v[k] = corners_of[c][k];
    child.level = level;
    child.parent = node;
    child.first_child = -1;
    child.base_face = n.base_face;
  }
  // Inner edges: corner child i's edge i + 1 faces the middle child.
  const auto add_adjacent = [this](int32_t a, int32_t b, int32_t c) {
    std::array<int32_t, 3>& across = adjacent_.emplace_back();
    across[0] = a;
    across[1] = b;
    across[2] = c;
  };
  add_adjacent(-1, first + 3, -1);
  add_adjacent(-1, -1, first + 3);
  add_adjacent(first + 3, -1, -1);
  add_adjacent(first + 1, first + 2, first);
  // Outer edges: the halves of edge e are edge e of children e and e + 1; the
  // neighbour's edge f runs the other way, so its child f meets our child
  // e + 1 and its child f + 1 meets our child e.
  for (int e = 0; e < 3; ++e) {
    const int32_t across = adjacent_[node][e];
    if (across < 0 || nodes_[across].first_child < 0) continue;
    const int32_t f = edge_index(across, n.v[next3(e)], n.v[e]);
    const int32_t other = nodes_[across].first_child;
    adjacent_[first + e][e] = other + next3(f);
    adjacent_[other + next3(f)][f] = first + e;
    adjacent_[first + next3(e)][e] = other + f;
    adjacent_[other + f][f] = first + next3(e);
  }
  nodes_[node].first_child = first;
  max_level_ = std::max(max_level_, level);
  if (static_cast<int32_t>(splits_at_level_.size()) < level) splits_at_level_.resize(level, 0);
  ++splits_at_level_[level - 1];
}

size_t TriangleHierarchy::level_triangle_bound(int32_t level) const {
  // Nodes of level l: the base triangles at 0, else 4 per split of level l - 1.
  const auto nodes_at = [this](int32_t l) -> size_t {
    if (l == 0) return base_face_count_;
    return l - 1 < static_cast<int32_t>(splits_at_level_.size()) ? 4 * splits_at_level_[l - 1] : 0;
  };
  const auto splits_at = [this](int32_t l) -> size_t {
    return l < static_cast<int32_t>(splits_at_level_.size()) ? splits_at_level_[l] : 0;
  };
  // Every node of level `level` is one triangle; a leaf of a coarser level is
  // one, or two when green-bisected.
  size_t bound = nodes_at(level);
  for (int32_t l = 0; l < level; ++l) bound += 2 * (nodes_at(l) - splits_at(l));
  return bound;
}

std::vector<std::array<int32_t, 3>> TriangleHierarchy::level_triangles(int32_t level,
                                                                     std::vector<int32_t>* node_of) const {
  level = std::clamp(level, 0, max_level_);
  std::vector<std::array<int32_t, 3>> out;
  if (node_of) node_of->clear();
  // Reserved once: grown by doubling, the finest mesh would be copied several
  // times over and leave pages touched for nothing (the decoder's output).
  out.reserve(level_triangle_bound(level));
  std::vector<int32_t> stack;
  // Depth first from each base triangle (nodes 0 .. F - 1), children in
  // order, so the triangles of one base face and of one subtree come together.
  for (int32_t root = 0; root < static_cast<int32_t>(nodes_.size()) && nodes_[root].parent < 0; ++root) {
    stack.push_back(root);
    while (!stack.empty()) {
      const int32_t t = stack.back();
      stack.pop_back();
      const Node& n = nodes_[t];
      if (n.first_child >= 0 && n.level < level) {
        for (int c = 3; c >= 0; --c) stack.push_back(n.first_child + c);
        continue;
      }
      int hanging = -1;
      if (n.level < level)  // a leaf: its split neighbours' midpoints (level n.level + 1) are present
        for (int e = 0; e < 3; ++e) {
          const int32_t across = adjacent_[t][e];
          if (across >= 0 && nodes_[across].first_child >= 0) {
            assert(hanging < 0 && "closure: two hanging vertices on one leaf");
            hanging = e;
          }
        }
      if (hanging < 0) {
        out.push_back(n.v);
        if (node_of) node_of->push_back(t);
        continue;
      }
      const int e = hanging;
      const int32_t across = adjacent_[t][e];
      const int32_t f = edge_index(across, n.v[next3(e)], n.v[e]);
      const int32_t m = nodes_[nodes_[across].first_child + f].v[next3(f)];
      const int32_t a = n.v[e], b = n.v[next3(e)], c = n.v[next3(next3(e))];
      out.push_back({a, m, c});
      out.push_back({m, b, c});
      if (node_of) node_of->insert(node_of->end(), 2, t);
    }
  }
  return out;
}

int32_t TriangleHierarchy::locate(const ParamPoint& p, int32_t level) const {
  if (p.face < 0 || p.face >= static_cast<int32_t>(nodes_.size()) || nodes_[p.face].parent >= 0) return -1;
  // Local barycentrics in the current node; clamped and renormalized each step
  // so rounding in points off the dyadic grid cannot push them out.
  Eigen::Vector3d w = p.bary;
  auto normalize = [](Eigen::Vector3d& x) {
    for (int i = 0; i < 3; ++i)
      if (!(x[i] > 0.0)) x[i] = 0.0;  // also NaN
    const double sum = x.sum();
    if (sum > 0.0 && sum < std::numeric_limits<double>::infinity())
      x /= sum;
    else
      x = Eigen::Vector3d::Constant(1.0 / 3.0);
  };
  normalize(w);
  int32_t t = p.face;
  while (nodes_[t].level < level && nodes_[t].first_child >= 0) {
    int child = 3;
    for (int i = 0; i < 3 && child == 3; ++i)
      if (w[i] > 0.5) child = i;
    if (child < 3) {
      w *= 2.0;  // child corner j != i is the midpoint of (i, j)
      w[child] -= 1.0;
    } else {
      w = Eigen::Vector3d(1.0 - 2.0 * w[2], 1.0 - 2.0 * w[0], 1.0 - 2.0 * w[1]);  // (m01, m12, m20)
    }
    normalize(w);
    t = nodes_[t].first_child + child;
  }
  return t;
}

}  // namespace srcodec
