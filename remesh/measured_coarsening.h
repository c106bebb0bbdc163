// Adaptivity by measured error (ours, not in the paper): once the whole
// refinement is built and fitted to the input (remesh/fit.h), the last
// level's splits are undone, those that gain least first, while the remesh's
// error against the input, estimated both ways as the project's metric
// measures it, stays within a given loss of the full refinement's.
//
// Why: the paper's Eq. 5 counts input vertices, and our earlier geometric
// tolerance judged each triangle by the input's distance to its plane before
// the fit. On a fitted remesh that follows a scan vertex to vertex (several
// triangles per input vertex), neither predicts what a split gains;
// measured on the fitted positions themselves, many splits go for little.
#pragma once

#include <cstddef>
#include <cstdint>

#include "format/mesh.h"
#include "format/status.h"
#include "remesh/fit.h"
#include "remesh/folds.h"
#include "format/semi_regular/semi_regular_mesh.h"

namespace srcodec {

struct CoarseningOptions {
  // The most the estimated PSNR may fall below the full refinement's, in dB.
  double max_loss_db = 0.5;
  size_t input_samples_per_vertex = 2;  // samples of the input's surface, per vertex of the finest level
  // Not the fit's (FitOptions::seed): the fit brings the remesh closest to
  // its own samples, so the error measured on them is too low.
  uint64_t seed = 7;
  // Then the vertices at the corners of the finest level's unsplit
  // triangles are fitted again (remesh/fit.h, with `fit`; they were fitted
  // to the children around them), the result's loss is measured whole, and
  // more splits are undone, in up to `refit_passes` passes in all, while the
  // refitted result stays within the limit.
  bool refit = true;
  FitOptions fit;
  int refit_passes = 3;
  // The passes after the first keep the whole measure within this part of
  // max_loss_db: the metric finds a larger loss than the whole measure does,
  // and the margin keeps the loss the metric sees within the one asked.
  double whole_margin = 0.7;
  // Deeper where it pays (ours): first, the finest level's triangles that
  // hold the most error (this fraction of them, by their share of the
  // estimated mean square both ways) are split once more, their new
  // vertices started at their parent edges' midpoints and fitted (without
  // `refit`, put on the input point nearest the midpoint).
  // The loss is then judged against the mesh before (the full refinement of
  // the levels asked), and the splits of both last levels may be undone.
  // 0 turns it off.
  double deepen_fraction = 0.0;
};

struct CoarseningReport {
  size_t candidates = 0;        // split triangles whose children are leaves (of the level below the finest, and
                                // with deepen_fraction of the one below it)
  size_t deepened = 0;          // triangles of the finest level asked split once more (deepen_fraction)
  size_t undone = 0;            // of those, the splits undone
  size_t triangles_before = 0;  // the finest level's
  size_t triangles_after = 0;
  double estimated_loss_db = 0.0;  // of the result, against the full refinement (the metric's own may differ a little)
  // Of the first pass's choice before its refit, measured as the refit one
  // (when there is none, estimated_loss_db).
  double estimated_loss_before_refit_db = 0.0;
  size_t refit = 0;                             // vertices fitted again
  int passes = 1;                               // choices made and kept
  size_t kept_for_folds = 0;       // splits kept because undoing them folded or pleated a triangle
  FoldCount folds;                 // the finest level's, after (as FitReport's)
  double seconds = 0.0;
};

// Undoes splits of the triangles of level L - 1 (L = mesh.levels) whose four
// children are leaves, in the order of what they gain: each one's squared
// distances to the input both ways (samples of the input to their nearest
// triangle of level L - 1 and of L; the triangle and its children to the
// input, each by the centroids of its sub-triangles), the directions
// weighted as the metric weighs them (per sample of the input, per unit
// area of the remesh). The fewest splits,
// taken in that order, with the balance and closure splits they bring
// (TriangleHierarchy::replayed), whose estimated PSNR (from the larger
// mean square of the two directions, as the metric's) is within
// max_loss_db of all splits'. A triangle left unsplit next to a split one
// is bisected (green) by the closure. Then the splits whose undoing left a
// triangle of the finest level folded or in a pleat (judged as the fit
// judges them, by the normals of `sides`, the oversampled input the
// remesher ran on) are put back, until none is. Vertices keep their
// positions, but with options.refit, the corners of the unsplit triangles
// (not the base's or the boundary's), which are fitted again to `input`;
// then further passes (CoarseningOptions::refit).
//
// Fails (kInvalidArgument) when max_loss_db is not in (0, 60].
StatusOr<SemiRegularMesh> coarsen_by_measured_error(const TriangleMesh& input, const TriangleMesh& sides,
                                                    const SemiRegularMesh& mesh, const CoarseningOptions& options,
                                                    CoarseningReport* report = nullptr);

}  // namespace srcodec
