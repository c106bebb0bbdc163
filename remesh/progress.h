// What the remesher reports as it goes: one RemeshProgress per step ended,
// with its figures. remesh/ builds no text; the command line writes the
// lines (tools/srcodec/remesh_progress.h), a library user may show its own.
#pragma once

#include <cstddef>
#include <functional>

namespace srcodec {

struct RemeshReport;
struct RefineLevelReport;
struct UntangleReport;
struct UnsplitReport;

enum class RemeshStep {
  kWholeInputIsBase,       // vertices: the input's; min_base_vertices: the smallest default base
  kComponents,             // report: components; vertices: theirs (a vertex at a cut non-manifold spot is
                           // counted in each piece); seconds: the split's
  kOversampled,            // report: oversample_steps, oversampled_vertices
  kBaseSizeRaised,         // vertices: the new default base size
  kFewerLevels,            // levels: those asked; vertices: what they need; report: oversampled_vertices
  kThresholdLevelByLevel,  // levels: those asked (too many for a uniform refinement first)
  kSites,                  // report: curled_sites, tip_sites, seconds_sites; vertices: the sites (all components)
  kBaseMesh,               // report: base_vertices, promoted_vertices, seconds_base; triangles: the
                           // base mesh's
  kRefineSetUp,            // vertices: the points placed on the base domain; seconds: the set-up's (their
                           // search trees, densities, normals and first cells)
  kLevel,                  // refine_level: the level built
  kThresholdStops,         // level: the level no triangle was selected for
  kSplitsUndone,           // refine_level: the repairs' counts after; triangles: left on the finest
                           // level; threshold, tolerance: the criteria that undid them
  kFit,                    // report->fit
  kMeasuredCoarsening,     // report->coarsening; level: the finest level before
  kUntangle,               // untangle: this run's report; wide: with the wide search
  kUnsplit,                // unsplit: this pass's report; coarser: at the coarser levels' tangles too;
                           // level: the level left whole; tangled_before, tangled_after (all levels); kept
  kSlivers,                // report->slivers; poor_quality: the quality a sliver is below
};

struct RemeshProgress {
  RemeshStep step = RemeshStep::kOversampled;
  double seconds = 0.0;  // the step's own
  const RemeshReport* report = nullptr;  // the report so far (not set by the refinement's own steps)
  const RefineLevelReport* refine_level = nullptr;
  const UntangleReport* untangle = nullptr;
  const UnsplitReport* unsplit = nullptr;
  int level = 0, levels = 0;
  size_t vertices = 0, min_base_vertices = 0, triangles = 0;
  size_t tangled_before = 0, tangled_after = 0;
  double poor_quality = 0.0;
  bool threshold = false, tolerance = false, wide = false, coarser = false, kept = false;
};

// May be empty: nothing reported.
using RemeshProgressCallback = std::function<void(const RemeshProgress&)>;

}  // namespace srcodec
