// Refinement of the base mesh into an adaptive semi-regular mesh (Kammoun,
// Payan, Antonini §III-B, Fig. 4 and 5, Eqs. 4-5; DESIGN.md remesh/ steps 6
// and 7): per level, split the selected triangles 1-to-4, start every new
// vertex at the input vertex nearest its edge's midpoint on the base domain,
// then run Lloyd relaxation over the sites of all levels so far. The
// paper's steps are refine.cpp, new_vertices.cpp and lloyd_relaxation.cpp;
// our repairs of the folds they leave are fold_repairs.cpp,
// patch_reparam.cpp and spike_mending.cpp (remesh/refiner.h holds the
// state they share).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "remesh/base_mesh.h"
#include "remesh/progress.h"
#include "format/semi_regular/hierarchy.h"

namespace srcodec {

struct RefineOptions {
  int levels = 4;  // levels to add above the base mesh, 0..12
  // Eq. 5's threshold: a triangle is split when g(t), the fewest input
  // vertices in the Voronoi cell of one of its three corners, exceeds it.
  // Counts are of the mesh refinement runs on (the oversampled input).
  double threshold = 0.0;
  bool uniform = false;  // split every triangle of every level, whatever g(t)
  // Eq. 5 judged on a uniform refinement: every level is split and relaxed
  // as with `uniform`, g(t) is taken from each level's relaxed cells, and
  // once the last level is relaxed every split with g(t) <= threshold is
  // undone with all below it. Off: each level splits only the selected
  // triangles and relaxes that adaptive mesh (the paper's order), which
  // costs less where the input is sparse but relaxes into worse tangles.
  bool threshold_after_uniform = false;
  // Geometric criterion (not the paper's), with Eq. 5 or uniform: once the
  // last level is relaxed, a split is undone (bottom up) where the RMS
  // distance from the input vertices under the split triangle to its plane
  // is within this (in the input's units). 0 turns it off.
  double tolerance = 0.0;
  // Lloyd steps per level; a level also stops when fewer than
  // min_moved_fraction of its sites moved in a step.
  int max_lloyd_iterations = 10;
  double min_moved_fraction = 0.002;
  RemeshProgressCallback progress;  // kLevel, kThresholdStops, kSplitsUndone
};

struct RefineLevelReport {
  int level = 0;               // the level built
  // Triangles of the level below to split: g(t) > threshold (with
  // threshold_after_uniform, those whose parent's split was kept).
  size_t selected = 0;
  size_t within_tolerance = 0;  // triangles of the level below whose split the tolerance undid
  size_t split = 0;            // triangles split, with balance and closure splits (those kept, with a tolerance)
  size_t vertices = 0;         // vertices of the level's mesh
  size_t triangles = 0;        // triangles of the level's mesh
  int lloyd_iterations = 0;
  size_t moves = 0;            // site moves accepted, summed over the steps
  size_t refused_folds = 0;    // site moves refused because a triangle would flip
  size_t empty_cells = 0;       // sites whose cell holds only their own vertex after the last step
  // Triangles facing against the input surface at the end (normal against
  // the summed input normals at their corners, or no area); 0 in a clean
  // remesh.
  size_t folded_triangles = 0;
  size_t coarse_folded_triangles = 0;  // the same, summed over the coarser levels' meshes
  // folded_triangles with every corner judged by the input vertex nearest
  // it. The remesher's own test judges a corner off the input (a midpoint,
  // a surface point, an untangled site) by the normal it was given when it
  // was placed, and its repairs aim at that test; this count does not share
  // it. Equal to folded_triangles when every corner is an input vertex.
  size_t folded_by_nearest_input = 0;
  // Edges of the level's mesh whose two triangles meet at more than 150
  // degrees (folded onto each other, whichever way they face).
  size_t pleats = 0;
  size_t untangled = 0;  // sites moved by the Laplacian untangling after Lloyd
  size_t spikes_mended = 0;  // sites brought back from another sheet, after the repairs (mend_spikes)
  // New vertices put at their parent edge's midpoint because no free input
  // vertex was near: the input is too coarse there (oversample more).
  size_t midpoint_vertices = 0;
  // New vertices put on the input surface between input vertices, because
  // the nearest free input vertex was far from their edge's midpoint.
  size_t surface_vertices = 0;
  // Sites moved off the input, to the mean of their neighbours, because no
  // input vertex undid a fold around them.
  size_t off_input_moves = 0;
  // Sites moved by the Laplacian smoothing of patches around folds that
  // single moves left (onto the input surface, between its vertices).
  size_t smoothed = 0;
  // Sites of this level put back at their parent edges' midpoints, off the
  // input, where nothing else undid the folds around them.
  size_t midpoint_resets = 0;
  // Sites moved onto the input by the last resort, a patch redrawn in a
  // planar map of the input under it (reparam_patch in refine.cpp).
  size_t reparameterized = 0;
  double seconds = 0.0;
};

struct RefineResult {
  TriangleHierarchy hierarchy;
  std::vector<Eigen::Vector3d> positions;  // per hierarchy vertex
  // Per hierarchy vertex: the input vertex it sits on (all distinct), or -1
  // for a vertex placed off the input (midpoint_vertices, off_input_moves).
  std::vector<int32_t> anchor;
};

// `input` is what the base mesh was built from (all components, disjoint);
// `base` its base mesh and parameterization.
StatusOr<RefineResult> refine(const TriangleMesh& input, const BaseMesh& base, const RefineOptions& options,
                              std::vector<RefineLevelReport>* report = nullptr);

}  // namespace srcodec
