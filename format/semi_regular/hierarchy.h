// The combinatorial side of adaptive semi-regular refinement (Kammoun, Payan,
// Antonini §III-B; DESIGN.md remesh/ steps 6-7): a forest of 1-to-4 split
// quadtrees, one per base triangle, kept balanced (triangles that share an
// edge differ by at most one level) and closed conformingly (red-green), so
// the mesh of every level is watertight wherever the base mesh is.
//
// Geometry lives elsewhere: this class only knows vertex ids, levels, parent
// edges and each vertex's nominal (dyadic) place on the base domain.
#pragma once

#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/memory_range.h"
#include "format/status.h"
#include "format/semi_regular/param.h"

namespace srcodec {

class TriangleHierarchy {
 public:
  struct Node {
    std::array<int32_t, 3> v{};  // corner vertex ids, in the base triangle's orientation
    int32_t level = 0;           // 0 for base triangles
    int32_t parent = -1;         // node id, -1 at level 0
    // -1 for a leaf; else children are first_child .. first_child + 3: the
    // corner children at v[0], v[1], v[2], then the middle one.
    int32_t first_child = -1;
    int32_t base_face = 0;
  };

  // Base triangles over vertices 0 .. base_vertex_count - 1: each directed
  // edge used at most once (manifold, consistently oriented), every vertex
  // used, no two triangles sharing all three edges (a closed two-triangle
  // component, whose refinement would join two vertices by two edges). Base
  // vertices keep their ids; new vertices are numbered on.
  static StatusOr<TriangleHierarchy> create(int32_t base_vertex_count,
                                            const std::vector<std::array<int32_t, 3>>& base_triangles);

  // (The accessors are inline: the decoder's forest and plan call them per vertex.)
  const std::vector<Node>& nodes() const { return nodes_; }
  int32_t vertex_count() const { return static_cast<int32_t>(vertex_level_.size()); }
  int32_t base_vertex_count() const { return base_vertex_count_; }
  int32_t max_level() const { return max_level_; }  // deepest node level, 0 before any split

  int32_t vertex_level(int32_t v) const {  // 0 for base vertices
    assert(v >= 0 && v < vertex_count());
    return vertex_level_[v];
  }
  std::array<int32_t, 2> parent_edge(int32_t v) const {  // {-1, -1} for base vertices
    assert(v >= 0 && v < vertex_count());
    return parent_edge_[v];
  }
  // The vertex's dyadic point: a base corner, or the midpoint (on the base
  // domain) of its parent edge. Computed on demand in O(level): only the
  // remesher asks, and the decoder's replay should not pay for it per split.
  ParamPoint nominal_param(int32_t v) const;

  // Capacity for this many nodes and vertices in all, so that a replay of
  // known size (the decoder knows its vertex counts) does not reallocate.
  void reserve(size_t nodes, size_t vertices);
  // The arrays' memory up to their capacity, to prefault (format/prefault.h)
  // before a replay writes it.
  std::vector<MemoryRange> reserved_memory() const;

  // Splits leaf `node` 1-to-4 (red). First splits, recursively, every coarser
  // leaf across its edges so the hierarchy stays balanced; afterwards splits
  // every same-level leaf left with two or three split neighbours, so the only
  // closure needed is a green bisection of triangles with one hanging vertex.
  // Appends the vertices this call created (in creation order) to
  // `new_vertices` if not null. A node that is already split is left alone.
  void split(int32_t node, std::vector<int32_t>* new_vertices = nullptr);

  // This hierarchy with only the splits that `keep` marks (one flag per
  // node; a marked node under an unmarked one stays unsplit) and the balance
  // and closure splits they need, replayed level by level over the same base
  // mesh. `old_vertex` and `old_node` (if not null) get, per vertex and per
  // node of the result, the vertex and the node at the same place here.
  StatusOr<TriangleHierarchy> replayed(const std::vector<char>& keep, std::vector<int32_t>* old_vertex = nullptr,
                                       std::vector<int32_t>* old_node = nullptr) const;

  // The watertight triangle mesh of level `level` (>= 0; levels beyond
  // max_level() give the finest mesh): nodes at levels <= level that are
  // leaves there, each with at most one hanging vertex (a midpoint of level
  // <= `level` on one edge) replaced by the two triangles of its green
  // bisection. Orientation is the base triangles'. Deterministic order.
  // With `node_of`, also the node each triangle comes from.
  std::vector<std::array<int32_t, 3>> level_triangles(int32_t level, std::vector<int32_t>* node_of = nullptr) const;

  // Number of vertices of level <= `level` (vertices are numbered by level:
  // all of level l come before any of level l + 1 only if refinement ran
  // level by level, so this counts, it does not slice).
  size_t level_vertex_count(int32_t level) const;

  // The node containing point `p` that is a leaf of the level-`level` mesh
  // (at level <= `level`, unsplit or split only below `level`). Points on
  // shared edges go to either side deterministically. -1 when p.face is not
  // a base triangle.
  int32_t locate(const ParamPoint& p, int32_t level) const;

  // Barycentrics of the node's corners v[0], v[1], v[2] in its base face
  // (dyadic, exact), recomputed from the path to the root: O(level).
  std::array<Eigen::Vector3d, 3> corner_bary(int32_t node) const;

 private:
  std::vector<Node> nodes_;
  // Per node: the node of the same level across edge i (v[i] -> v[i+1]), or
  // -1 when there is none yet (the region across is coarser) or the edge is on
  // the base boundary. Replaces edge and midpoint hash maps (see hierarchy.cpp).
  std::vector<std::array<int32_t, 3>> adjacent_;
  // Per vertex.
  std::vector<int32_t> vertex_level_;
  std::vector<std::array<int32_t, 2>> parent_edge_;
  // Where the vertex was made: 3 node + e for the midpoint of edge e of node
  // (a new vertex), 3 base face + corner for a base vertex.
  std::vector<int32_t> vertex_origin_;
  std::vector<int32_t> pending_;  // split()'s work stack, kept to reuse its memory
  std::vector<size_t> vertices_at_level_;  // how many vertices each level created
  std::vector<size_t> splits_at_level_;    // how many nodes of each level are split
  size_t base_face_count_ = 0;
  int32_t base_vertex_count_ = 0;
  int32_t max_level_ = 0;

  int32_t coarser_leaf_across(int32_t node) const;
  int32_t split_neighbour_count(int32_t node) const;
  int32_t edge_index(int32_t node, int32_t a, int32_t b) const;
  void split_balanced(int32_t node, std::vector<int32_t>* new_vertices);
  // At least the number of triangles level_triangles(level) lists (0 <= level <= max_level).
  size_t level_triangle_bound(int32_t level) const;
};

}  // namespace srcodec
