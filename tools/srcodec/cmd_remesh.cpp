// `srcodec remesh MESH -o OUT`: adaptive Voronoi semi-regular remeshing
// (Kammoun, Payan, Antonini), with per-level size and error against the input.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <utility>

#include "format/file_io.h"
#include "format/mesh_files/mesh_io.h"
#include "remesh/remesher.h"
#include "remesh/surface_distance.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"
#include "tools/srcodec/remesh_flags.h"
#include "tools/srcodec/remesh_progress.h"

namespace srcodec {
namespace {

struct RemeshCliOptions {
  std::string input, output, write_levels;
  RemeshFlags remesh;
  bool json = false, quiet = false;
  size_t samples = 200000;
};

// The refinement's counts of one level, for --json.
void add_level_fields(const RefineLevelReport& lr, JsonWriter& j) {
  j.field("selected", lr.selected)
      .field("within_tolerance", lr.within_tolerance)
      .field("split", lr.split)
      .field("lloyd_iterations", lr.lloyd_iterations)
      .field("moves", lr.moves)
      .field("refused_folds", lr.refused_folds)
      .field("folded_triangles", lr.folded_triangles)
      .field("coarse_folded_triangles", lr.coarse_folded_triangles)
      .field("folded_by_nearest_input", lr.folded_by_nearest_input)
      .field("pleats", lr.pleats)
      .field("untangled", lr.untangled)
      .field("midpoint_vertices", lr.midpoint_vertices)
      .field("surface_vertices", lr.surface_vertices)
      .field("off_input_moves", lr.off_input_moves)
      .field("smoothed", lr.smoothed)
      .field("midpoint_resets", lr.midpoint_resets)
      .field("reparameterized", lr.reparameterized)
      .field("spikes_mended", lr.spikes_mended)
      .field("empty_cells", lr.empty_cells);
}

// The --json object: the remesh's report and, per level, `levels`.
JsonWriter summary_json(const RemeshCliOptions& o, const TriangleMesh& input, const RemeshOptions& options,
                        const RemeshReport& report, double seconds, const std::vector<JsonWriter>& level_json) {
  JsonWriter j;
  j.field("input", o.input)
      .field("output", o.output)
      .field("input_vertices", input.positions.size())
      .field("components", report.components)
      .field("oversample_steps", report.oversample_steps)
      .field("oversampled_vertices", report.oversampled_vertices)
      .field("base_vertices", report.base_vertices)
      .field("promoted_vertices", report.promoted_vertices)
      .field("crease_vertices_kept", report.crease_vertices_kept)
      .field("base_crease_edges", report.base_crease_edges)
      .field("crease_edge_share", report.crease_edge_share)
      .field("curled_sites", report.curled_sites)
      .field("tip_sites", report.tip_sites)
      .field("uniform", options.uniform)
      .field("threshold", options.threshold)
      .field("threshold_after_uniform", report.threshold_after_uniform)
      .field("tolerance_db", options.tolerance_db)
      .field("fit_surface", options.fit_surface)
      .field("fit_moved", report.fit.moved)
      .field("fit_refused", report.fit.refused)
      .field("fit_mean_offset", report.fit.mean_offset)
      .field("fit_folded_by_nearest_input", report.fit.folded_by_nearest_input)
      .field("fit_pleats", report.fit.pleats)
      .field("untangle", options.fit_surface && options.untangle)
      .field("untangle_moved", report.untangle.moved)
      .field("untangle_joint_moved", report.untangle.joint_moved)
      .field("untangle_rounds", report.untangle.rounds)
      .field("untangle_seconds", report.untangle.seconds)
      .field("slivers_moved", report.slivers.moved)
      .field("slivers_before", report.slivers.poor_before)
      .field("slivers_after", report.slivers.poor_after)
      .field("untangled_folded_by_nearest_input", report.untangle.after.folded)
      .field("untangled_pleats", report.untangle.after.pleats)
      .field("untangled_coarser_folded_by_nearest_input", report.untangle.after.coarser_folded)
      .field("untangled_coarser_pleats", report.untangle.after.coarser_pleats)
      .field("unsplit_tangles", options.unsplits())
      .field("unsplit_passes", report.unsplit.passes)
      .field("unsplit_stars", report.unsplit.stars)
      .field("unsplit_splits", report.unsplit.undone)
      .field("unsplit_seconds", report.unsplit.seconds)
      .field("max_loss_db", options.max_loss_db);
  if (options.max_loss_db > 0.0)
    j.field("deepen_fraction", options.deepen_fraction)
        .field("coarsening_deepened", report.coarsening.deepened)
        .field("coarsening_candidates", report.coarsening.candidates)
        .field("coarsening_undone", report.coarsening.undone)
        .field("coarsening_estimated_loss_db", report.coarsening.estimated_loss_db)
        .field("coarsening_kept_for_folds", report.coarsening.kept_for_folds)
        .field("coarsening_estimated_loss_before_refit_db", report.coarsening.estimated_loss_before_refit_db)
        .field("coarsening_refit", report.coarsening.refit)
        .field("coarsening_passes", report.coarsening.passes)
        .field("coarsening_seconds", report.coarsening.seconds)
        .field("coarsened_folded_by_nearest_input", report.coarsening.folds.folded_by_nearest_input)
        .field("coarsened_pleats", report.coarsening.folds.pleats);
  std::vector<JsonWriter> places;
  for (const TangledPlace& place : report.tangled_places) {
    JsonWriter pj;
    pj.field("x", place.centre.x())
        .field("y", place.centre.y())
        .field("z", place.centre.z())
        .field("radius", place.radius)
        .field("folded", place.count.folded)
        .field("coarser_folded", place.count.coarser_folded)
        .field("pleats", place.count.pleats)
        .field("coarser_pleats", place.count.coarser_pleats);
    places.push_back(pj);
  }
  j.array("tangled_places", places)
      .field("seconds", seconds)
      .array("levels", level_json);
  return j;
}

// The tangles left: the goal is none; where some are left, the user
// should know (the JSON has them per level and place).
void print_tangles_left(const RemeshReport& report, int levels) {
  const RefineLevelReport* last = report.levels.empty() ? nullptr : &report.levels.back();
  const TangleCount& left = report.untangle.after;
  if (report.untangle.rounds > 0) {  // the untangling's count, of the output
    if (left.total() > 0) {
      std::printf("folds: %zu triangle(s) of level %d and %zu of coarser levels face against the input (corners "
                  "judged by its nearest vertices); %zu and %zu edge(s) pleat (their triangles meet at more than "
                  "150 degrees)\n",
                  left.folded, levels, left.coarser_folded, left.pleats, left.coarser_pleats);
      // Where, the largest places first (all of them in the JSON).
      constexpr size_t kPlacesShown = 5;
      const auto& places = report.tangled_places;
      for (size_t i = 0; i < std::min(places.size(), kPlacesShown); ++i) {
        const TangledPlace& p = places[i];
        std::printf("  at (%.6g, %.6g, %.6g), within %.3g: %zu + %zu folded, %zu + %zu pleats\n", p.centre.x(),
                    p.centre.y(), p.centre.z(), p.radius, p.count.folded, p.count.coarser_folded, p.count.pleats,
                    p.count.coarser_pleats);
      }
      if (places.size() > kPlacesShown)
        std::printf("  and %zu more place(s) (--json lists them all)\n", places.size() - kPlacesShown);
    }
  } else if (last && last->folded_triangles + last->coarse_folded_triangles + last->pleats > 0) {
    std::printf("folds: %zu triangle(s) of level %d and %zu of coarser levels face against the input; %zu edge(s) "
                "pleat (their triangles meet at more than 150 degrees)\n",
                last->folded_triangles, last->level, last->coarse_folded_triangles, last->pleats);
  }
}

Status run_remesh(const RemeshCliOptions& o) {
  SRCODEC_ASSIGN_OR_RETURN(RemeshOptions options, to_remesh_options(o.remesh));
  SRCODEC_RETURN_IF_ERROR(check_output_path(o.output));
  if (!o.write_levels.empty()) SRCODEC_RETURN_IF_ERROR(check_output_path(o.write_levels + "_l0.obj"));
  if (!o.quiet)
    options.progress =
        remesh_progress_lines([](const std::string& line) { std::cerr << "remesh: " << line << std::endl; });
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh input, read_mesh_with_progress(o.input, o.quiet, "remesh: "));
  const auto start = std::chrono::steady_clock::now();
  RemeshReport report;
  SRCODEC_ASSIGN_OR_RETURN(SemiRegularMesh srm, remesh(input, options, &report));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  SurfaceDistanceOptions distance_options;
  distance_options.samples_per_surface = o.samples;
  std::vector<JsonWriter> level_json;
  if (!o.json) {
    std::printf("%s: %zu vertices, %zu triangles, %zu component(s); oversampled %d time(s) (%zu vertices)\n",
                o.input.c_str(), input.positions.size(), input.triangles.size(), report.components,
                report.oversample_steps, report.oversampled_vertices);
    std::printf("%5s %10s %10s %12s %9s %8s\n", "level", "vertices", "triangles", "rms", "psnr_db", "seconds");
  }
  TriangleMesh finest;
  for (int32_t level = 0; level <= srm.levels; ++level) {
    TriangleMesh mesh = srm.level_mesh(level);
    SRCODEC_ASSIGN_OR_RETURN(SurfaceDistance d, surface_distance(input, mesh, distance_options));
    const double level_seconds = level == 0 ? report.seconds_oversample + report.seconds_sites + report.seconds_base
                                            : report.levels[level - 1].seconds;
    if (!o.write_levels.empty()) {
      const std::string path = o.write_levels + "_l" + std::to_string(level) + ".obj";
      SRCODEC_RETURN_IF_ERROR(write_mesh(mesh, path));
    }
    if (o.json) {
      JsonWriter j;
      j.field("level", level)
          .field("vertices", mesh.positions.size())
          .field("triangles", mesh.triangles.size())
          .field("rms", d.rms)
          .field("psnr", d.psnr)
          .field("seconds", level_seconds);
      if (level > 0) add_level_fields(report.levels[level - 1], j);
      level_json.push_back(j);
    } else {
      std::printf("%5d %10zu %10zu %12.6g %9.2f %8.2f\n", level, mesh.positions.size(), mesh.triangles.size(),
                  d.rms, d.psnr, level_seconds);
    }
    if (level == srm.levels) finest = std::move(mesh);
  }
  SRCODEC_RETURN_IF_ERROR(write_mesh(finest, o.output));
  if (o.json) {
    std::cout << summary_json(o, input, options, report, seconds, level_json).str() << "\n";
  } else {
    print_tangles_left(report, srm.levels);
    std::printf("wrote %s (level %d) in %.2f s\n", o.output.c_str(), srm.levels, seconds);
  }
  return ok_status();
}

}  // namespace

Command add_remesh_command(CommandLine& cli, bool experiment) {
  auto o = std::make_shared<RemeshCliOptions>();
  Subcommand& cmd = cli.add_command(
      "remesh", "Adaptive semi-regular remeshing (Voronoi/Lloyd, Kammoun-Payan-Antonini) with per-level error");
  cmd.positional("mesh", o->input, "Input mesh (OBJ, PLY, OFF, STL)");
  cmd.option("-o,--output", o->output, "Finest level, written as OBJ or PLY").required();
  add_remesh_flags(cmd, o->remesh);
  if (experiment) add_experiment_flags(cmd, o->remesh);
  cmd.option("--write-levels", o->write_levels, "Also write every level to PREFIX_l<level>.obj");
  cmd.option("--samples", o->samples, "Samples per surface for the error figures")
      .range(size_t{1000}, size_t{100000000})
      .show_default();
  cmd.flag("--json", o->json, "Print one JSON object");
  cmd.flag("-q,--quiet", o->quiet, "No progress lines on stderr");
  return {&cmd, [o] { return run_remesh(*o); }};
}

}  // namespace srcodec
