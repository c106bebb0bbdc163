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

 private:
  struct Out {
    int32_t to, third;  // the directed edge (a, to) lies in the triangle (a, to, third)
  };
  std::vector<uint32_t> begin_;  // per vertex + 1: a's outgoing edges are out_[begin_[a] .. begin_[a + 1])
  std::vector<Out> out_;
  std::vector<int32_t> valence_;
  std::vector<uint8_t> boundary_;
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

}  // namespace srcodec
