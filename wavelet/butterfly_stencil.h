// The modified Butterfly prediction stencil (Zorin, Schröder, Sweldens,
// "Interpolating Subdivision for Meshes with Arbitrary Topology", SIGGRAPH
// 1996, §4; boundary rule as in OpenMesh's ModifiedButterflyT) on one level
// mesh of a semi-regular hierarchy. Internal to wavelet/: LiftingPlan::build
// turns each stencil into wings or flat taps once, the transforms never traverse.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "format/status.h"
#include "wavelet/lifting.h"

namespace srcodec {

// A manifold triangle mesh as directed edges grouped by their first vertex
// (CSR, built by counting sort in O(triangles)): the triangle (a, b, c) holding
// the directed edge (a, b) is found by scanning a's few outgoing edges.
class LevelMesh {
 public:
  // Fails when a directed edge is used twice (not manifold or not oriented)
  // or a corner is out of [0, vertex_count).
  static StatusOr<LevelMesh> build(const std::vector<std::array<int32_t, 3>>& triangles, int32_t vertex_count);

  // Third corner of the triangle holding the directed edge (a, b); -1 if none.
  int32_t third(int32_t a, int32_t b) const {
    for (uint32_t i = begin_[a]; i < begin_[a + 1]; ++i)
      if (out_[i].to == b) return out_[i].third;
    return -1;
  }
  bool has_edge(int32_t a, int32_t b) const { return third(a, b) >= 0 || third(b, a) >= 0; }
  int32_t valence(int32_t v) const { return valence_[v]; }  // distinct neighbours
  bool on_boundary(int32_t v) const { return boundary_[v] != 0; }
  int32_t vertex_count() const { return static_cast<int32_t>(valence_.size()); }
  // The directed edges (a, b) with a triangle on their left and none across,
  // by increasing a.
  std::vector<std::array<int32_t, 2>> boundary_edges() const;

 private:
  struct Out {
    int32_t to, third;  // the directed edge (a, to) lies in the triangle (a, to, third)
  };
  std::vector<uint32_t> begin_;  // per vertex + 1: a's outgoing edges are out_[begin_[a] .. begin_[a + 1])
  std::vector<Out> out_;
  std::vector<int32_t> valence_;
  std::vector<uint8_t> boundary_;
};

// The sharp edges of one level mesh: its creases and its boundary edges, as
// each vertex's list of sharp neighbours (CSR; a vertex has a few at most).
// Only built for levels that have creases: the stencils below then treat
// each side of a crease as if the crease were its boundary (Hoppe et al.,
// "Piecewise Smooth Surface Reconstruction", SIGGRAPH 1994; Biermann, Levin,
// Zorin, "Piecewise Smooth Subdivision Surfaces with Normal Control",
// SIGGRAPH 2000). wavelet/README.md, "Creases".
class SharpEdges {
 public:
  // `creases`: edges (a, b) of `mesh`, a < b, no repeats (any order). Fails
  // when one is not an edge of the mesh.
  static StatusOr<SharpEdges> build(const LevelMesh& mesh, const std::vector<std::array<int32_t, 2>>& creases);

  // Whether the vertex has a crease edge: it then counts as a boundary
  // vertex of the mesh cut open along the creases.
  bool crease_vertex(int32_t v) const { return crease_vertex_[v] != 0; }
  bool crease(int32_t a, int32_t b) const {
    const Edge* e = find(a, b);
    return e && e->crease;
  }
  bool sharp(int32_t a, int32_t b) const { return find(a, b) != nullptr; }
  // Number of sharp edges at v (a crease that is also a boundary edge counts once).
  int32_t degree(int32_t v) const { return static_cast<int32_t>(begin_[v + 1] - begin_[v]); }
  // The next vertex after p along the sharp curve through the sharp edge
  // (p, q), away from q: p's other sharp neighbour when p has exactly two;
  // -1 when the curve ends at p (a corner of 3+ sharp edges, or an end).
  int32_t curve_neighbour(int32_t p, int32_t q) const {
    if (degree(p) != 2) return -1;
    const int32_t first = edges_[begin_[p]].to;
    return first != q ? first : edges_[begin_[p] + 1].to;
  }

 private:
  struct Edge {
    int32_t to;
    bool crease;  // else a boundary edge
  };
  // The sharp edge (a, b) among a's, or null.
  const Edge* find(int32_t a, int32_t b) const {
    for (uint32_t i = begin_[a]; i < begin_[a + 1]; ++i)
      if (edges_[i].to == b) return &edges_[i];
    return nullptr;
  }
  std::vector<uint32_t> begin_;  // per vertex + 1: v's sharp edges are edges_[begin_[v] .. begin_[v + 1])
  std::vector<Edge> edges_;
  std::vector<uint8_t> crease_vertex_;
};

// Appends to `taps` the stencil predicting the new vertex on edge (a, b) of
// `mesh` (which must hold the edge): weights summing to 1, one tap per
// distinct vertex, sorted by vertex id, no zero weights. `left` and `right`
// are mesh.third(a, b) and mesh.third(b, a), which the caller has already
// looked up (the plan keeps them for the frames).
// The four wings of the plain 8-point stencil of edge (a, b), in the order
// LiftingPlan::Odd::wing lists them, when butterfly_taps would give that
// stencil: the 8-point rule applies and every wing is a vertex (no
// reflection across a boundary edge). {-1, -1, -1, -1} otherwise.
std::array<int32_t, 4> regular_wings(const LevelMesh& mesh, int32_t a, int32_t b, int32_t left, int32_t right);

void butterfly_taps(const LevelMesh& mesh, int32_t a, int32_t b, int32_t left, int32_t right,
                    std::vector<LiftingPlan::Tap>* taps);

// The same on the mesh cut open along the creases of `sharp`
// (wavelet/README.md, "Creases"): a crease edge, or a boundary edge with a
// crease vertex at an end, takes the 4-point curve rule along its sharp
// curve (a ghost point 2p - q where the curve ends at p); any other edge the
// rules above with every crease as a boundary edge. With no creases in
// `sharp`, the same stencils as above.
std::array<int32_t, 4> regular_wings(const LevelMesh& mesh, const SharpEdges& sharp, int32_t a, int32_t b,
                                     int32_t left, int32_t right);
void butterfly_taps(const LevelMesh& mesh, const SharpEdges& sharp, int32_t a, int32_t b, int32_t left,
                    int32_t right, std::vector<LiftingPlan::Tap>* taps);

// LiftingPlan::Odd's update divisor of end v of the parent edge (v, w): v's
// valence, but for a crease vertex kCurveUpdateDivisor when (v, w) is sharp
// and v has two sharp edges, else 0 (no update: a corner or an end of a
// crease, or an edge off its curve).
uint32_t update_divisor(const LevelMesh& mesh, const SharpEdges& sharp, int32_t v, int32_t w);

}  // namespace srcodec
