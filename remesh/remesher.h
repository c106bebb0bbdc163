// The whole remesher (Kammoun, Payan, Antonini; DESIGN.md remesh/ steps
// 1-7): components, oversampling, LBG + Lloyd sites, base mesh by collapses
// with its parameterization, then adaptive refinement with Lloyd.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"
#include "remesh/fit.h"
#include "remesh/relax_slivers.h"
#include "remesh/unsplit_tangles.h"
#include "remesh/untangle.h"
#include "remesh/measured_coarsening.h"
#include "remesh/oversample.h"
#include "remesh/progress.h"
#include "remesh/refine.h"
#include "format/semi_regular/semi_regular_mesh.h"

namespace srcodec {

enum class CreaseMode {
  kAuto,    // where the creases long enough to follow take kAutoCreaseEdgeShare of the base's edges
  kKeep,    // wherever a crease curve is long enough for the base to follow
  kIgnore,  // never
};

struct RemeshOptions {
  int levels = 4;  // 0..12
  // `levels` is an upper bound, as when the user did not choose it: a mesh
  // too small for it gets as many levels as its vertices support, and one
  // with fewer vertices than the smallest default base mesh becomes the base
  // mesh itself (no levels). Only with the default base size.
  bool fit_levels = false;
  // Base mesh vertices over all components; 0 picks default_base_vertices.
  size_t base_vertices = 0;
  // The paper's adaptivity (Eq. 5): a triangle is split when each corner's
  // Voronoi cell holds more than this many vertices of the oversampled input.
  double threshold = 0.0;
  bool uniform = false;  // split everything; the threshold is then unused
  // Geometric criterion (RefineOptions::tolerance; ours, kept for the
  // experiments that compare it with Eq. 5) as a PSNR in dB, the metric's
  // scale: after the last level, a triangle's split is undone where the
  // input's RMS distance to its plane is within the bounding-box diagonal x
  // 10^(-dB/20). Applies with uniform or the threshold; 0 turns it off.
  double tolerance_db = 0.0;
  // Adaptive by measured error (remesh/measured_coarsening.h, ours): after
  // the uniform refinement and the fit, the last level's splits that gain
  // least are undone while the estimated PSNR stays within this many dB of
  // the full refinement's; with fit_surface, the corners of the triangles
  // left unsplit are then fitted again, and more splits undone while the
  // result stays within it. Needs `uniform`, no tolerance; 0 turns it off.
  double max_loss_db = 0.0;
  // With max_loss_db (CoarseningOptions::deepen_fraction, ours): first split
  // once more this fraction of the finest level's triangles, those holding
  // the most error, and judge the loss against the levels asked; the
  // splits of both last levels may then be undone, so the result can have
  // one level more than `levels` where that pays. 0 turns it off.
  double deepen_fraction = 0.0;
  int oversample = -1;     // Butterfly/Loop steps 0..3; -1 = auto, per component (remesher.cpp)
  OversampleScheme scheme = OversampleScheme::kButterfly;
  int max_lloyd_iterations = 10;  // per refinement level
  // Bytes the remesh may take; 0: what the machine has available
  // (remesh/memory_budget.h). An input whose oversampling would need more is
  // refused before the work starts, with the estimate and what would fit.
  uint64_t memory_limit = 0;
  // After the refinement, move the vertices above the base mesh off the
  // input's vertices, along their normals, to centre the finest level's
  // triangles on the input surface (remesh/fit.h; ours): a site on an input
  // vertex leaves the chord's sag between vertices. Boundary vertices stay.
  // Off: every vertex where the paper's method put it (the paper's runs).
  bool fit_surface = true;
  // With fit_surface, last: move the vertices of the triangles still folded
  // or in a pleat to nearby places that leave fewer of them
  // (remesh/untangle.h; ours). With max_loss_db also before the coarsening,
  // whose loss is then judged against the untangled full refinement.
  bool untangle = true;
  // With untangle, after it: where triangles are still folded or in a
  // pleat, the splits of the level below the finest around them undone
  // (remesh/unsplit_tangles.h; ours), then untangled again. Off for every
  // caller: an adaptive last level costs its refinement flags in every
  // prefix of a coded file (docs/remesh_design.md, "Unsplitting").
  bool unsplit_tangles = false;
  // Whether the unsplitting runs: it needs the fit and the untangling.
  bool unsplits() const { return fit_surface && untangle && unsplit_tangles; }
  // With fit_surface, last: the finest level's own vertices at slivers move
  // along their tangent plane where that makes the triangles around them
  // rounder (remesh/relax_slivers.h; ours): slivers are where coding error
  // turns triangles over.
  bool relax_slivers = true;
  // Whether to keep the input's creases (remesh/features.h,
  // remesh/base_creases.h) as chains of base edges, their corners and ends
  // as base vertices, and the vertices refining those edges on the creases;
  // recorded in SemiRegularMesh::crease_edges for the wavelet's crease
  // rules. By default only where they are a real share of the shape
  // (kAutoCreaseEdgeShare): on inputs with a few creases, keeping them moves
  // the rate-distortion both ways (docs/remesh_design.md, "Creases").
  CreaseMode creases = CreaseMode::kAuto;
  RemeshProgressCallback progress;  // after each step (remesh/progress.h), may be empty
};

struct RemeshReport {
  size_t components = 0;
  int oversample_steps = 0;                   // the most any component got
  std::vector<int> component_oversample_steps;  // per component, in split_into_manifold_components's order
  size_t oversampled_vertices = 0;
  size_t base_vertices = 0;       // including promoted ones
  size_t promoted_vertices = 0;   // non-sites the base mesh had to keep (see build_base_mesh)
  size_t crease_vertices_kept = 0;  // of those, on creases (RemeshOptions::creases)
  size_t base_crease_edges = 0;     // base edges along the input's creases (RemeshOptions::creases)
  // The share of the base's edges the creases long enough to follow would
  // take (remesh/base_creases.h, kAutoCreaseEdgeShare), kept or not; 0 with
  // CreaseMode::kIgnore.
  double crease_edge_share = 0.0;
  size_t curled_sites = 0;        // sites added to split cells that wrap around thin parts (kMinCellFlatness)
  size_t tip_sites = 0;           // sites added at the tips of narrow holes (remesh/boundary_tips.h)
  // The threshold was judged on a uniform refinement (RefineOptions), not
  // level by level: the input held enough vertices for one.
  bool threshold_after_uniform = false;
  double seconds_oversample = 0.0, seconds_sites = 0.0, seconds_base = 0.0, seconds_refine = 0.0;
  std::vector<RefineLevelReport> levels;
  FitReport fit;  // with RemeshOptions::fit_surface
  CoarseningReport coarsening;  // with RemeshOptions::max_loss_db
  // With RemeshOptions::fit_surface and untangle; every run summed (with
  // max_loss_db, and with each unsplitting pass kept; `before` the first's,
  // `after` the last kept's: the output's).
  UntangleReport untangle;
  // With RemeshOptions::unsplit_tangles: the passes kept, and in them the
  // stars left whole and the splits undone. The seconds count every pass's
  // unsplitting (its untangling is in `untangle`).
  struct Unsplitting {
    int passes = 0;
    size_t stars = 0, undone = 0;
    double seconds = 0.0;
  } unsplit;
  SliverRelaxReport slivers;  // with RemeshOptions::relax_slivers
  // Where the output's tangles are (remesh/untangle.h), when the untangling
  // ran and left any: places within kTangledPlaceReach of the bounding box's
  // diagonal of each other are one.
  std::vector<TangledPlace> tangled_places;
};
constexpr double kTangledPlaceReach = 0.02;

// The default base size: the larger the base mesh, the less the
// parameterization is stretched (the main limit on quality), so as many base
// vertices as the oversampling budget allows with about 8 input vertices per
// finest-level vertex, at most one per 24 input vertices, at least 4 per
// component, and between 100 and 4000 in all.
size_t default_base_vertices(size_t input_vertices, size_t components, int levels);

// Remeshes a cleaned triangle mesh (format/'s clean_mesh output); each
// connected component gets its own base mesh, its share of the base
// vertices in proportion to its vertex count, and (with oversample = -1) its
// own number of oversampling steps. Errors (kInvalidArgument) explain what
// would work when the mesh is too small for the base size or levels asked.
StatusOr<SemiRegularMesh> remesh(const TriangleMesh& mesh, const RemeshOptions& options,
                                 RemeshReport* report = nullptr);

}  // namespace srcodec
