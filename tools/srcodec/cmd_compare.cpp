// `srcodec compare REF TEST`: symmetric Metro-style surface distance, and
// what a viewer sees differ (tools/measure/visual_difference.h).
#include <cstdio>
#include <iostream>
#include <memory>

#include "format/mesh_files/mesh_io.h"
#include "tools/measure/surface_distance.h"
#include "tools/measure/visual_difference.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"
#include "tools/srcodec/visual_flags.h"

namespace srcodec {
namespace {

struct CompareOptions {
  std::string reference, test;
  size_t samples = 200000;
  uint64_t seed = 1;
  VisualOptions visual;
  bool no_visual = false;
  bool json = false;
};

JsonWriter directed_json(const DirectedDistance& d) {
  JsonWriter j;
  j.field("rms", d.rms).field("mean", d.mean).field("max", d.max).field("samples", d.samples);
  return j;
}

JsonWriter visual_json(const VisualDifference& v, const VisualOptions& o) {
  JsonWriter j;
  j.field("mean_normal_degrees", v.mean_normal_degrees)
      .field("defect_share", v.defect_share)
      .field("defect_degrees", o.defect_degrees)
      .field("depth_psnr", v.depth_psnr)
      .field("turned_over_share", v.turned_over_share)
      .field("views", o.views)
      .field("resolution", o.resolution)
      .field("pixels", v.pixels);
  return j;
}

Status run_compare(const CompareOptions& o) {
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh reference, read_triangle_mesh(o.reference));
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh test, read_triangle_mesh(o.test));
  SurfaceDistanceOptions options;
  options.samples_per_surface = o.samples;
  options.seed = o.seed;
  SRCODEC_ASSIGN_OR_RETURN(SurfaceDistance d, cgal_surface_distance(reference, test, options));
  VisualDifference v;
  if (!o.no_visual) {
    SRCODEC_ASSIGN_OR_RETURN(v, visual_difference(reference, test, o.visual));
  }
  if (o.json) {
    JsonWriter j;
    j.field("reference", o.reference)
        .field("test", o.test)
        .field("rms", d.rms)
        .field("hausdorff", d.hausdorff)
        .field("psnr", d.psnr)
        .field("diag", d.diag)
        .object("ref_to_test", directed_json(d.ref_to_test))
        .object("test_to_ref", directed_json(d.test_to_ref));
    if (!o.no_visual) j.object("visual", visual_json(v, o.visual));
    std::cout << j.str() << "\n";
    return ok_status();
  }
  auto line = [](const char* name, const DirectedDistance& x) {
    std::printf("  %-12s rms %-12.6g mean %-12.6g max %-12.6g (%zu samples)\n", name, x.rms, x.mean, x.max, x.samples);
  };
  std::printf("%s -> %s\n", o.reference.c_str(), o.test.c_str());
  line("ref -> test", d.ref_to_test);
  line("test -> ref", d.test_to_ref);
  std::printf("  rms %.6g  hausdorff %.6g  diag %.6g  psnr %.2f dB\n", d.rms, d.hausdorff, d.diag, d.psnr);
  if (!o.no_visual) {
    std::printf("  seen from %d views at %dx%d: mean normal angle %.3f deg, %.3f%% of pixels differ by over %g deg,\n",
                o.visual.views, o.visual.resolution, o.visual.resolution, v.mean_normal_degrees, 100.0 * v.defect_share,
                o.visual.defect_degrees);
    std::printf("  depth psnr %.2f dB; %.4f%% of the test surface's area turned over\n", v.depth_psnr,
                100.0 * v.turned_over_share);
  }
  return ok_status();
}

}  // namespace

Command add_compare_command(CommandLine& cli) {
  auto o = std::make_shared<CompareOptions>();
  Subcommand& cmd = cli.add_command("compare", "Surface distance (RMS, Hausdorff, PSNR) and visual difference between two meshes");
  cmd.positional("reference", o->reference, "Reference mesh (its bounding-box diagonal sets the PSNR scale)");
  cmd.positional("test", o->test, "Mesh to measure against the reference");
  cmd.option("--samples", o->samples, "Area-uniform samples on each surface")
      .range(size_t{1000}, size_t{100000000})
      .show_default();
  cmd.option("--seed", o->seed, "Sampling seed").show_default();
  add_visual_flags(cmd, o->visual, o->no_visual, "Surface distance only: no renders, no turned-over area");
  cmd.flag("--json", o->json, "Print one JSON object");
  return {&cmd, [o] { return run_compare(*o); }};
}

}  // namespace srcodec
