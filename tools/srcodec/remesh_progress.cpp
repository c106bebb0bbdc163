#include "tools/srcodec/remesh_progress.h"

#include <chrono>
#include <iostream>
#include <utility>

#include "format/mesh_files/mesh_io.h"
#include "remesh/remesher.h"

namespace srcodec {
namespace {

std::string n(size_t v) { return std::to_string(v); }
std::string n(int v) { return std::to_string(v); }
std::string n(double v) { return std::to_string(v); }

std::string level_line(const RefineLevelReport& lr) {
  std::string tangles;  // the goal is none; say so when some are left
  if (lr.folded_triangles + lr.coarse_folded_triangles > 0)
    tangles += ", " + n(lr.folded_triangles) + " folded (" + n(lr.coarse_folded_triangles) + " on coarser levels)";
  if (lr.pleats > 0) tangles += ", " + n(lr.pleats) + " pleats";
  if (lr.spikes_mended > 0) tangles += ", " + n(lr.spikes_mended) + " spikes mended";
  return "level " + n(lr.level) + ": " + n(lr.vertices) + " vertices, " + n(lr.triangles) + " triangles, " +
         n(lr.lloyd_iterations) + " Lloyd steps" + tangles + ", " + n(lr.seconds) + " s";
}

std::string untangle_line(const UntangleReport& r, bool wide) {
  const TangleCount &was = r.before, &now = r.after;
  auto counts = [](size_t folded, size_t pleats) { return n(folded) + " folded, " + n(pleats) + " pleats"; };
  return std::string(wide ? "untangle (wide search): " : "untangle: ") + n(r.moved) + " moves (" + n(r.joint_moved) +
         " joint) in " + n(r.rounds) + " rounds; finest level " + counts(was.folded, was.pleats) + " -> " +
         counts(now.folded, now.pleats) + "; coarser levels " + counts(was.coarser_folded, was.coarser_pleats) +
         " -> " + counts(now.coarser_folded, now.coarser_pleats) + ", " + n(r.seconds) + " s";
}

std::string coarsening_line(const CoarseningReport& c, int levels) {
  const std::string deepened =
      c.deepened > 0 ? n(c.deepened) + " triangles of level " + n(levels) + " split once more; " : "";
  return "measured coarsening: " + deepened + n(c.undone) + " of " + n(c.candidates) + " splits of level " +
         (c.deepened > 0 ? n(levels - 1) + " and " + n(levels) : n(levels - 1)) + " undone, " +
         n(c.triangles_before) + " -> " + n(c.triangles_after) + " triangles, estimated loss " +
         n(c.estimated_loss_db) + " dB (" + n(c.kept_for_folds) + " kept where undoing them folded or pleated; " +
         n(c.refit) + " vertices fitted again, " + n(c.passes) + " pass(es), " +
         n(c.estimated_loss_before_refit_db) + " dB before the first refit); then " +
         n(c.folds.folded_by_nearest_input) + " folded (recount), " + n(c.folds.pleats) + " pleats, " +
         n(c.seconds) + " s";
}

}  // namespace

std::string remesh_progress_line(const RemeshProgress& p) {
  const RemeshReport* r = p.report;
  switch (p.step) {
    case RemeshStep::kWholeInputIsBase:
      return "the input has " + n(p.vertices) + " vertices, fewer than the smallest default base mesh (" +
             n(p.min_base_vertices) + "): it is the base mesh, with no levels";
    case RemeshStep::kOversampled:
      return "oversampled (up to " + n(r->oversample_steps) + " steps per component): " + n(r->oversampled_vertices) +
             " vertices, " + n(p.seconds) + " s";
    case RemeshStep::kComponents:
      return "components: " + n(r->components) + " (manifold, " + n(p.vertices) + " vertices), " + n(p.seconds) + " s";
    case RemeshStep::kBaseSizeRaised:
      return "default base size raised to " + n(p.vertices) +
             " vertices: the oversampled input holds more vertices than planned";
    case RemeshStep::kFewerLevels:
      return n(p.levels) + " levels need about " + n(p.vertices) + " input vertices, the input has " +
             n(r->oversampled_vertices) + (r->oversample_steps > 0 ? " after oversampling" : "") + ": trying " +
             n(p.levels - 1);
    case RemeshStep::kThresholdLevelByLevel:
      return "threshold: the input is too sparse for " + n(p.levels) +
             " uniform levels; Eq. 5 decides level by level (the paper's order)";
    case RemeshStep::kSites:
      return "sites: " + n(p.vertices) + " (" + n(r->curled_sites) + " added in curled cells, " + n(r->tip_sites) +
             " at the tips of narrow holes), " + n(r->seconds_sites) + " s";
    case RemeshStep::kBaseMesh:
      return "base mesh: " + n(r->base_vertices) + " vertices (" + n(r->promoted_vertices) +
             " kept by the collapses), " + n(p.triangles) + " triangles, " + n(r->seconds_base) + " s";
    case RemeshStep::kRefineSetUp:
      return "refinement set up: " + n(p.vertices) + " points on the base mesh, " + n(p.seconds) + " s";
    case RemeshStep::kLevel:
      return level_line(*p.refine_level);
    case RemeshStep::kThresholdStops:
      return "level " + n(p.level) + ": no triangle passes the threshold; refinement stops";
    case RemeshStep::kSplitsUndone: {
      const RefineLevelReport& lr = *p.refine_level;
      const std::string criteria = p.threshold && p.tolerance ? "threshold and tolerance"
                                   : p.threshold               ? "threshold"
                                                               : "tolerance";
      return criteria + ": " + n(p.triangles) + " triangles left, " + n(lr.folded_triangles) + " folded (" +
             n(lr.coarse_folded_triangles) + " on coarser levels), " + n(lr.pleats) + " pleats, " + n(p.seconds) +
             " s";
    }
    case RemeshStep::kFit:
      return "fit: " + n(r->fit.moved) + " vertices moved off the input (mean " + n(r->fit.mean_offset) + "), " +
             n(r->fit.refused) + " moves undone where a triangle would turn, fold or pleat; then " +
             n(r->fit.folded_by_nearest_input) + " folded (recount), " + n(r->fit.pleats) + " pleats, " +
             n(r->fit.seconds) + " s";
    case RemeshStep::kMeasuredCoarsening:
      return coarsening_line(r->coarsening, p.level);
    case RemeshStep::kUntangle:
      return untangle_line(*p.untangle, p.wide);
    case RemeshStep::kUnsplit:
      return "unsplit" + std::string(p.coarser ? " (coarser levels too)" : "") + ": " + n(p.unsplit->stars) +
             " stars of level " + n(p.level) + " left whole (" + n(p.unsplit->undone) +
             " splits undone) and untangled again: tangled triangles, all levels, " + n(p.tangled_before) + " -> " +
             n(p.tangled_after) + (p.kept ? ", kept" : ", not kept");
    case RemeshStep::kSlivers:
      return "slivers: " + n(r->slivers.moved) + " moves; finest triangles of quality below " +
             n(p.poor_quality).substr(0, 4) + ": " + n(r->slivers.poor_before) + " -> " + n(r->slivers.poor_after) +
             ", " + n(r->slivers.seconds) + " s";
  }
  return "";
}

RemeshProgressCallback remesh_progress_lines(std::function<void(const std::string&)> say) {
  return [say = std::move(say)](const RemeshProgress& p) { say(remesh_progress_line(p)); };
}

StatusOr<TriangleMesh> read_mesh_with_progress(const std::string& path, bool quiet, const std::string& prefix) {
  const auto start = std::chrono::steady_clock::now();
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh mesh, read_triangle_mesh(path));
  if (!quiet)
    std::cerr << prefix << "read: " << n(mesh.positions.size()) << " vertices, " << n(mesh.triangles.size())
              << " triangles (cleaned), " << n(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count())
              << " s" << std::endl;
  return mesh;
}

}  // namespace srcodec
