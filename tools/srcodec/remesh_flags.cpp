#include "tools/srcodec/remesh_flags.h"

#include <algorithm>

namespace srcodec {

void add_remesh_flags(Subcommand& cmd, RemeshFlags& f) {
  f.levels_option = &cmd.option("--levels", f.levels,
                                "Refinement levels above the base mesh (without this option: fewer for "
                                "inputs too small for 4, none below 100 vertices)")
                         .range(0, 12)
                         .show_default();
  cmd.option("--base-vertices", f.base_vertices,
             "Base mesh vertices (default: from the input size and levels, 100..4000; up to a quarter more "
             "where cells wrap around thin parts; see docs/remesh_design.md)");
  auto& threshold = cmd.option("--threshold", f.threshold,
                               "The paper's adaptivity (Eq. 5): keep a triangle's split only when each corner's "
                               "Voronoi cell holds more than this many (oversampled) input vertices; judged on a "
                               "uniform refinement where the input is dense enough for one, else level by level")
                        .finite()
                        .non_negative();
  cmd.flag("--uniform", f.uniform, "Split every triangle (the default without --threshold)").excludes(threshold);
  auto& max_loss =
      cmd.option("--max-loss", f.max_loss_db,
                 "Adaptive by measured error: refine uniformly and fit, then undo the last level's splits that "
                 "gain least (error measured both ways against the input) while the estimated PSNR stays within "
                 "this many dB of the full refinement's; the unsplit triangles' corners are fitted again, and "
                 "more splits undone while the result stays within it; e.g. 0.5")
          .finite()
          .range(0.01, 60.0)
          .excludes(threshold);
  f.max_loss_option = &max_loss;
  cmd.option("--deepen", f.deepen_fraction,
             "With --max-loss: first split once more this fraction of the finest level's triangles, those "
             "holding the most error, then judge the loss against the levels asked and undo the splits of "
             "both last levels that gain least: the output has one level more than --levels where that pays; "
             "e.g. 0.06")
      .finite()
      .range(0.0, 1.0)
      .needs(max_loss);
  cmd.option("--oversample", f.oversample, "Subdivision steps before remeshing: auto, 0, 1, 2 or 3").show_default();
  cmd.option("--scheme", f.scheme,
             "Oversampling scheme: butterfly (the paper's), loop (the paper's comparison, its Fig. 6), or linear "
             "(ours: keeps the input's facets)")
      .show_default();
  cmd.option("--creases", f.creases,
             "Keep the input's sharp creases as base edges, their corners as base vertices, recorded in the file "
             "and predicted along by the coding: auto (where they are a real share of the shape, as on CAD parts), "
             "keep (every crease long enough for the base mesh to follow) or off (docs/remesh_design.md, Creases)")
      .show_default();
}

void add_experiment_flags(Subcommand& cmd, RemeshFlags& f) {
  auto& tolerance = cmd.option("--tolerance", f.tolerance_db,
                               "Adaptive by geometry (ours): after the last level, undo a triangle's split where "
                               "the input's RMS distance to it is within this PSNR in dB (bounding-box diagonal x "
                               "10^(-dB/20)); with --uniform or --threshold")
                        .finite()
                        .range(1.0, 300.0);
  if (f.max_loss_option) tolerance.excludes(*f.max_loss_option);
  cmd.negated_flag("--no-fit-surface", f.fit_surface,
                   "Leave every vertex where the paper's method put it (on the input's vertices): no fit to the "
                   "input surface, no untangling, no sliver relaxation");
  cmd.negated_flag("--no-untangle", f.untangle,
                   "After the fit, leave the vertices of triangles still folded or in a pleat where they are");
  cmd.negated_flag("--no-relax-slivers", f.relax_slivers, "Leave the finest level's slivers as they are");
  cmd.flag("--unsplit-tangles", f.unsplit_tangles,
           "After the untangling, where triangles stay folded or in a pleat, leave the level below the finest "
           "whole around one of their corners and untangle again, while that leaves fewer such triangles "
           "(costs bytes when coded: see docs/remesh_design.md, \"Unsplitting\")");
}

StatusOr<RemeshOptions> to_remesh_options(const RemeshFlags& o) {
  RemeshOptions r;
  r.levels = o.levels;
  r.fit_levels = o.levels_option == nullptr || !o.levels_option->given();
  r.base_vertices = o.base_vertices;
  if (o.uniform && o.threshold >= 0.0)
    return invalid_argument("--uniform and --threshold exclude each other (uniform is threshold 0 with every "
                            "triangle split)");
  // Without --threshold the remesh is uniform; every cell holds at least its
  // own site's vertex, so epsilon 0 would split everything anyway.
  r.uniform = o.uniform || o.threshold < 0.0;
  r.threshold = std::max(o.threshold, 0.0);
  r.tolerance_db = o.tolerance_db;
  r.max_loss_db = o.max_loss_db;
  r.deepen_fraction = o.deepen_fraction;
  r.fit_surface = o.fit_surface;
  r.untangle = o.untangle;
  r.unsplit_tangles = o.unsplit_tangles;
  r.relax_slivers = o.relax_slivers;
  if (o.creases == "auto") {
    r.creases = CreaseMode::kAuto;
  } else if (o.creases == "keep") {
    r.creases = CreaseMode::kKeep;
  } else if (o.creases == "off") {
    r.creases = CreaseMode::kIgnore;
  } else {
    return invalid_argument("--creases " + o.creases + ": use auto, keep or off");
  }
  if (o.oversample == "auto") {
    r.oversample = -1;
  } else if (o.oversample.size() == 1 && o.oversample[0] >= '0' && o.oversample[0] <= '3') {
    r.oversample = o.oversample[0] - '0';
  } else {
    return invalid_argument("--oversample " + o.oversample + ": use auto, 0, 1, 2 or 3");
  }
  SRCODEC_ASSIGN_OR_RETURN(r.scheme, parse_oversample_scheme(o.scheme, "--scheme"));
  return r;
}

}  // namespace srcodec
