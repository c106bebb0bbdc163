#include "codec/encode_mesh.h"

#include <chrono>
#include <cmath>
#include <string>

namespace srcodec {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The most segment bytes whose file fits a byte budget.
StatusOr<uint64_t> cut_within_budget(const StreamCutter& cutter, uint64_t budget, uint64_t minimum) {
  if (budget < minimum)
    return invalid_argument("a budget of " + std::to_string(budget) + " bytes is below the " +
                            std::to_string(minimum) + " bytes that the header, base mesh and refinement flags "
                            "take (use fewer base vertices or levels)");
  return cutter.segment_bytes_within(budget);
}

// The fewest segment bytes that reach a PSNR target.
StatusOr<uint64_t> cut_for_psnr(const StreamCutter& cutter, double target) {
  SRCODEC_ASSIGN_OR_RETURN(double best, whole_stream_psnr(cutter));
  if (best < target)
    return invalid_argument("a PSNR of " + number_text(target) + " dB is out of reach: the whole stream gives " +
                            number_text(best) + " dB, limited by the remesh (use more levels or base vertices)");
  return segment_bytes_for_psnr(cutter, target);
}

// The segment bytes `rate` asks for; with the knee, `knee` says where the
// search stopped.
StatusOr<uint64_t> choose_cut(const StreamCutter& cutter, const Rate& rate, size_t input_vertices,
                              uint64_t minimum, Knee* knee) {
  switch (rate.kind) {
    case Rate::Kind::kBytes:
      return cut_within_budget(cutter, static_cast<uint64_t>(rate.value), minimum);
    case Rate::Kind::kBitsPerVertex:
      return cut_within_budget(
          cutter, static_cast<uint64_t>(std::floor(rate.value * static_cast<double>(input_vertices) / 8.0)),
          minimum);
    case Rate::Kind::kPsnr:
      return cut_for_psnr(cutter, rate.value);
    case Rate::Kind::kKnee:
      break;
  }
  SRCODEC_ASSIGN_OR_RETURN(*knee, knee_of_stream(cutter, input_vertices));
  return knee->segment_bytes;
}

// The remesher's steps a library user sees as encode stages; the rest are
// notes on the way (a base size raised, fewer levels), not stages.
const char* remesh_stage(RemeshStep step) {
  switch (step) {
    case RemeshStep::kOversampled: return "oversample";
    case RemeshStep::kSites: return "sites";
    case RemeshStep::kBaseMesh: return "base mesh";
    case RemeshStep::kLevel: return "level";
    case RemeshStep::kFit: return "fit";
    case RemeshStep::kMeasuredCoarsening: return "coarsen";
    case RemeshStep::kUntangle: return "untangle";
    case RemeshStep::kSlivers: return "slivers";
    default: return nullptr;
  }
}

}  // namespace

StatusOr<MeshEncodeResult> encode_mesh(const TriangleMesh& input, const MeshEncodeOptions& options) {
  const Clock::time_point start = Clock::now();
  const auto step_done = [&](const char* stage, int level = 0) {
    if (options.progress) options.progress(EncodeProgress{stage, level, seconds_since(start)});
  };
  MeshEncodeResult out;

  RemeshOptions remesh_options = options.remesh;
  if (options.progress)
    remesh_options.progress = [&, theirs = options.remesh.progress](const RemeshProgress& p) {
      if (theirs) theirs(p);
      if (const char* stage = remesh_stage(p.step))
        step_done(stage, p.step == RemeshStep::kLevel && p.refine_level != nullptr ? p.refine_level->level : 0);
    };
  SRCODEC_ASSIGN_OR_RETURN(SemiRegularMesh semi_regular, remesh(input, remesh_options, &out.remesh));
  out.seconds_remesh = seconds_since(start);
  step_done("remesh");

  const Clock::time_point coding_start = Clock::now();
  SRCODEC_ASSIGN_OR_RETURN(EncodedSrm encoded, encode_srm(semi_regular, input, options.coding));
  out.seconds_coding = seconds_since(coding_start);
  out.header = encoded.header;
  out.crease_edges = semi_regular.crease_edges.size();
  out.full_stream_bytes = encoded.bytes.size();
  step_done("code");

  const Clock::time_point rate_start = Clock::now();
  const StreamCutter cutter(input, encoded.bytes);
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> smallest, cutter.cut(0));
  out.minimum_bytes = smallest.size();
  SRCODEC_ASSIGN_OR_RETURN(uint64_t segment_bytes, choose_cut(cutter, options.rate, input.positions.size(),
                                                              out.minimum_bytes, &out.knee));
  SRCODEC_ASSIGN_OR_RETURN(out.file, cutter.cut(segment_bytes));
  out.seconds_rate = seconds_since(rate_start);
  step_done("rate");

  SRCODEC_ASSIGN_OR_RETURN(out.psnr, cutter.psnr(segment_bytes, options.samples));
  step_done("measure");
  return out;
}

}  // namespace srcodec
