// The exact nearest point of a triangle mesh to a query point, through a
// bounding-volume hierarchy of axis-aligned boxes over the triangles
// (median split on the longest axis, as in Ericson, "Real-Time Collision
// Detection", 2005, §6.2), searched nearest box first and pruned by the
// distance to each box. Exact, unlike NearestTriangle's centroid search:
// the metric (remesh/surface_distance.h) measures with it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "remesh/geometry.h"
namespace srcodec {

class TriangleTree {
 public:
  using Hit = TriangleHit;

  // Over the triangles listed in `faces` (indices into `triangles`), or all
  // of them when `faces` is empty. Copies the corners: the arrays need not
  // outlive the tree. Indices must be valid (the caller checks them).
  TriangleTree(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<int32_t, 3>>& triangles,
               const std::vector<uint32_t>& faces = {});

  // The nearest point of all the triangles; on a tie, the first found (the
  // same for the same tree and query). Thread-safe: the tree is only read.
  Hit closest(const Eigen::Vector3d& q) const;
  size_t size() const { return face_.size(); }

 private:
  struct Node {
    Eigen::Vector3d lo, hi;  // the box of its triangles
    uint32_t first = 0;      // a leaf: its triangles' slots; else: its first child (the second follows)
    uint32_t count = 0;      // triangles of a leaf, 0 for an inner node
  };
  // Fills nodes_[node] over slots order_[begin, end), splitting below it,
  // its descendants from nodes_[descendants] on (in the order a serial
  // depth-first build would number them; `subtree_nodes`: how many nodes a
  // subtree over so many triangles has). Large halves are built in parallel.
  void build(uint32_t node, uint32_t descendants, uint32_t begin, uint32_t end,
             const std::vector<Eigen::Vector3d>& centroids, const std::vector<std::pair<uint32_t, uint32_t>>& subtree_nodes);
  static double box_squared(const Node& n, const Eigen::Vector3d& q);

  std::vector<std::array<Eigen::Vector3d, 3>> corners_;  // per slot, in leaf order
  std::vector<int32_t> face_;                            // per slot: the mesh's triangle
  std::vector<Node> nodes_;                              // nodes_[0] is the root
  std::vector<uint32_t> order_;                          // while building: slots in tree order
};

}  // namespace srcodec
