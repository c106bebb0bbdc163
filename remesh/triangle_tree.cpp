#include "remesh/triangle_tree.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <numeric>
#include <utility>

#include "remesh/geometry.h"

namespace srcodec {
namespace {

// Triangles per leaf: few enough that a leaf costs about as much as a box.
constexpr uint32_t kLeafSize = 4;
// Deeper than a balanced tree over 2^32 triangles can be (two entries a level).
constexpr int kMaxStack = 80;
// Subtrees over fewer triangles are built on the thread that splits them.
constexpr uint32_t kParallelBuild = 8192;

// Per size of a subtree (in triangles) the halves split it into take, the
// number of its nodes: a leaf is one, a split one more than its halves. A
// balanced tree has at most two sizes a level. Sorted by size.
std::vector<std::pair<uint32_t, uint32_t>> subtree_node_counts(uint32_t n) {
  std::vector<std::pair<uint32_t, uint32_t>> counts;
  const auto count = [&](auto&& self, uint32_t m) -> uint32_t {
    for (const auto& [size, nodes] : counts)
      if (size == m) return nodes;
    const uint32_t nodes = m <= kLeafSize ? 1 : 1 + self(self, m / 2) + self(self, m - m / 2);
    counts.emplace_back(m, nodes);
    return nodes;
  };
  count(count, n);
  std::sort(counts.begin(), counts.end());
  return counts;
}

uint32_t nodes_over(const std::vector<std::pair<uint32_t, uint32_t>>& counts, uint32_t m) {
  return std::lower_bound(counts.begin(), counts.end(), std::make_pair(m, uint32_t{0}))->second;
}

}  // namespace

TriangleTree::TriangleTree(const std::vector<Eigen::Vector3d>& positions,
                           const std::vector<std::array<int32_t, 3>>& triangles, const std::vector<uint32_t>& faces) {
  const size_t n = faces.empty() ? triangles.size() : faces.size();
  if (n == 0) return;
  std::vector<std::array<Eigen::Vector3d, 3>> corners(n);
  std::vector<int32_t> face(n);
  std::vector<Eigen::Vector3d> centroids(n);
  for (size_t i = 0; i < n; ++i) {
    face[i] = static_cast<int32_t>(faces.empty() ? i : faces[i]);
    const auto& t = triangles[static_cast<size_t>(face[i])];
    for (int k = 0; k < 3; ++k) corners[i][static_cast<size_t>(k)] = positions[static_cast<size_t>(t[static_cast<size_t>(k)])];
    centroids[i] = (corners[i][0] + corners[i][1] + corners[i][2]) / 3.0;
  }
  // Build over a permutation, then store the corners in leaf order so that a
  // leaf's triangles sit together in memory.
  corners_ = std::move(corners);
  face_ = std::move(face);
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0u);
  const std::vector<std::pair<uint32_t, uint32_t>> counts = subtree_node_counts(static_cast<uint32_t>(n));
  nodes_.resize(nodes_over(counts, static_cast<uint32_t>(n)));
  build(0, 1, 0, static_cast<uint32_t>(n), centroids, counts);
  std::vector<std::array<Eigen::Vector3d, 3>> sorted_corners(n);
  std::vector<int32_t> sorted_face(n);
  for (size_t i = 0; i < n; ++i) {
    sorted_corners[i] = corners_[order_[i]];
    sorted_face[i] = face_[order_[i]];
  }
  corners_ = std::move(sorted_corners);
  face_ = std::move(sorted_face);
  order_.clear();
  order_.shrink_to_fit();
}

void TriangleTree::build(uint32_t node, uint32_t descendants, uint32_t begin, uint32_t end,
                         const std::vector<Eigen::Vector3d>& centroids,
                         const std::vector<std::pair<uint32_t, uint32_t>>& subtree_nodes) {
  if (end - begin <= kLeafSize) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (uint32_t i = begin; i < end; ++i)
      for (const Eigen::Vector3d& p : corners_[order_[i]]) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    nodes_[node].lo = lo;
    nodes_[node].hi = hi;
    nodes_[node].first = begin;
    nodes_[node].count = end - begin;
    return;
  }
  // The box of the centroids, to choose the split axis (the node's own box
  // is its children's, once they are built).
  Eigen::Vector3d clo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), chi = -clo;
  for (uint32_t i = begin; i < end; ++i) {
    clo = clo.cwiseMin(centroids[order_[i]]);
    chi = chi.cwiseMax(centroids[order_[i]]);
  }
  int axis = 0;
  (chi - clo).maxCoeff(&axis);
  const uint32_t mid = begin + (end - begin) / 2;
  // Ties broken by slot: the same tree on every platform.
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](uint32_t a, uint32_t b) {
    const double ca = centroids[a][axis], cb = centroids[b][axis];
    return ca < cb || (ca == cb && a < b);
  });
  const uint32_t child = descendants;
  nodes_[node].first = child;
  const uint32_t second_descendants = child + 2 + nodes_over(subtree_nodes, mid - begin) - 1;
  const auto first_half = [&] { build(child, child + 2, begin, mid, centroids, subtree_nodes); };
  const auto second_half = [&] { build(child + 1, second_descendants, mid, end, centroids, subtree_nodes); };
  if (end - begin >= kParallelBuild) {
    tbb::parallel_invoke(first_half, second_half);
  } else {
    first_half();
    second_half();
  }
  nodes_[node].lo = nodes_[child].lo.cwiseMin(nodes_[child + 1].lo);
  nodes_[node].hi = nodes_[child].hi.cwiseMax(nodes_[child + 1].hi);
}

double TriangleTree::box_squared(const Node& n, const Eigen::Vector3d& q) {
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({n.lo[k] - q[k], 0.0, q[k] - n.hi[k]});
    sum += gap * gap;
  }
  return sum;
}

TriangleTree::Hit TriangleTree::closest(const Eigen::Vector3d& q) const {
  Hit best;
  if (nodes_.empty()) return best;
  struct Entry {
    uint32_t node;
    double squared;  // to its box: no triangle in it is nearer
  };
  Entry stack[kMaxStack];
  int top = 0;
  stack[top++] = {0, box_squared(nodes_[0], q)};
  while (top > 0) {
    const Entry e = stack[--top];
    if (e.squared > best.squared) continue;
    const Node& n = nodes_[e.node];
    if (n.count > 0) {
      for (uint32_t s = n.first; s < n.first + n.count; ++s) {
        Eigen::Vector3d c;
        const double d = squared_distance_to_triangle(q, corners_[s][0], corners_[s][1], corners_[s][2], c);
        if (d < best.squared) best = {face_[s], c, d};
      }
      continue;
    }
    // The nearer child is searched first (pushed last): it likely holds the
    // answer, and then prunes much of the farther one.
    Entry a{n.first, box_squared(nodes_[n.first], q)}, b{n.first + 1, box_squared(nodes_[n.first + 1], q)};
    if (a.squared < b.squared) std::swap(a, b);
    if (a.squared <= best.squared) stack[top++] = a;
    if (b.squared <= best.squared) stack[top++] = b;
  }
  return best;
}

}  // namespace srcodec
