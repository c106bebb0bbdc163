// The untangling (ours, not in the paper): after the fit, the vertices of
// the triangles still folded or in a pleat move, one at a time, to the
// nearby place that leaves fewest such triangles around them, on every level.
//
// The refinement's repairs (remesh/refine.cpp) work on sites, which stay on
// input vertices, and judge a corner by the normal its site was given; the
// fit (remesh/fit.h) only refuses moves that would fold more. What both
// leave is mostly where the input's sheets come closer than a finest edge
// (lips, claws, ears), and a few spots of smooth scans.
// There a vertex placed anywhere near, not only on an input vertex, often
// unfolds its triangles.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "remesh/fit.h"
#include "remesh/folds.h"
#include "remesh/levels_to_move.h"

namespace srcodec {

struct UntangleOptions {
  int rounds = 16;              // passes over the tangled vertices, while one moves any
  size_t input_candidates = 8;  // input vertices tried around a vertex's neighbours' centroid
  size_t joint_vertices = 40;   // the most vertices moved together (0: no joint moves)
  // Input vertices tried for a vertex that may only move onto input vertices
  // (fixed[v] == 2): those nearest it and those nearest its neighbours'
  // centroid, each as many, on its own component of the input (0: such
  // vertices stay where they are).
  size_t input_vertex_hops = 32;
  // A wider search for a free vertex (fixed[v] == 0): also the input
  // vertices nearest it and those nearest its neighbours' centroid, this
  // many each (0: none). The remesher runs one pass with it, last, where
  // triangles stay tangled after the unsplitting (remesh/remesher.cpp).
  size_t wide_candidates = 0;
};

// The triangles judged tangled (as FoldCounter judges them), on the finest
// level and on the coarser ones together.
struct TangleCount {
  size_t folded = 0;  // facing against the input normals at their corners
  size_t pleats = 0;  // pairs of neighbours meeting at more than 150 degrees
  size_t coarser_folded = 0, coarser_pleats = 0;
  size_t total() const { return folded + pleats + coarser_folded + coarser_pleats; }
};

struct UntangleReport {
  size_t moved = 0;  // moves kept, over all rounds
  size_t joint_moved = 0;  // joint moves kept
  int rounds = 0;    // rounds run
  TangleCount before, after;
  double seconds = 0.0;
};

// What the untangling looks up in the input (`sides`): its vertices' sides
// and a search over them, and its components. Built once and kept across
// calls on one input (the remesher untangles up to nine times).
class UntangleInput {
 public:
  explicit UntangleInput(const TriangleMesh& sides);  // keeps a reference to it
  const TriangleMesh& mesh() const { return mesh_; }
  const FoldCounter::Sides& side_at() const { return side_at_; }
  // Per vertex of `sides`, its edge-connected component.
  const std::vector<int32_t>& component() const { return component_; }

 private:
  const TriangleMesh& mesh_;
  FoldCounter::Sides side_at_;
  std::vector<int32_t> component_;
};

// Moves vertices of `levels` (each level's triangles over `positions`; the
// last is the finest) to leave fewer triangles of any level folded against
// the normals of the vertices of `sides` (the oversampled input the remesher
// ran on) nearest their corners, or in a pleat. A vertex with fixed[v] == 0
// moves freely; with fixed[v] == 2 (LevelsToMove::kOnInputVertices: a base
// vertex, which stays an input vertex) only onto other vertices of `sides`
// (UntangleOptions::input_vertex_hops); any other stays. Each round takes
// the vertices of the tangled triangles and their neighbours on the finest
// level, in increasing order, and tries for each free one:
// points toward its neighbours' centroid (also pressed onto the tangent
// plane of the input there), the input vertices nearest that centroid,
// points toward each neighbour, and, where a linear program finds one within
// half the mean edge around the vertex, a point where every triangle at it
// faces along its corners' sides (the deepest such point, and the one
// nearest the vertex on the way there), and with wide_candidates the input
// vertices nearest the vertex and its centroid; for a base vertex, the input
// vertices of its component nearest it and nearest its neighbours'
// centroid. The one leaving the fewest folded triangles and pleats around
// the vertex, all levels counted, is kept when that is
// fewer than before, or as many but half as deep (by how far past folded
// and past 150 degrees they are, summed), which lets a later move finish
// what this one began. Up to `rounds` rounds, while any vertex moves.
// Then the tangled triangles' vertices, joined through them into clusters
// and each cluster grown by its finest ring (up to `joint_vertices`
// movable vertices), move together: a linear program over all their moves
// at once, each corner's side held, finds where the folded triangles face
// out while the others keep facing out, step by step (up to 12 steps a
// cluster), each step kept when it leaves fewer tangled triangles there (or
// as many, less deep), the reach halved after a step not kept and doubled
// back after one kept; then rounds again, twice at most.
// Deterministic.
UntangleReport untangle(const UntangleInput& sides, const std::vector<std::vector<std::array<int32_t, 3>>>& levels,
                        const std::vector<char>& fixed, std::vector<Eigen::Vector3d>* positions,
                        const UntangleOptions& options = {});
// The same with the input's UntangleInput built for this call.
UntangleReport untangle(const TriangleMesh& sides, const std::vector<std::vector<std::array<int32_t, 3>>>& levels,
                        const std::vector<char>& fixed, std::vector<Eigen::Vector3d>* positions,
                        const UntangleOptions& options = {});

// Where tangles are left, for the user (`srcodec remesh` prints the largest
// places): the folded triangles and the pleats of every level, judged and
// counted as UntangleReport::after counts them, a fold at its triangle's
// centroid and a pleat at the mean of its two triangles' centroids, gathered
// into places: a tangle joins the place of every other within `reach` of it
// (single linkage). The places' counts sum to the whole's.
struct TangledPlace {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // the mean of its tangles' points
  double radius = 0.0;                                // the farthest of them from the centre
  TangleCount count;
};
// Most tangles first (then by centre, x first, for a stable order).
std::vector<TangledPlace> tangled_places(const UntangleInput& sides,
                                         const std::vector<std::vector<std::array<int32_t, 3>>>& levels,
                                         const std::vector<Eigen::Vector3d>& positions, double reach);

}  // namespace srcodec
