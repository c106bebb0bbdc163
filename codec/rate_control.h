// Rate control over an embedded .srm stream: which prefix of its
// coefficient segments to keep for a byte budget, a PSNR target or the knee
// of its rate-distortion curve. Cuts are decoded and measured against the
// input with the encoder's own estimate of the metric
// (remesh/surface_distance.h, our triangle tree); on the way to the knee,
// most are only estimated from how far they lie from the whole stream's
// mesh (codec/cut_estimate.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "codec/cut_estimate.h"
#include "format/mesh.h"
#include "format/status.h"
#include "remesh/surface_distance.h"

namespace srcodec {

// The file that keeps the first `segment_bytes` bytes of coefficient
// segments (truncate_srm), its size, and the PSNR against the input of the
// mesh it decodes to, measured or estimated. Holds references: `input` and
// `full` must outlive it. A `full` that does not parse has no segment
// bytes, and its cuts fail. Thread-safe: knee_of_stream judges two cuts at
// once.
class StreamCutter {
 public:
  StreamCutter(const TriangleMesh& input, const std::vector<uint8_t>& full);
  uint64_t segment_bytes() const { return segment_bytes_; }
  StatusOr<std::vector<uint8_t>> cut(uint64_t segment_bytes) const;
  StatusOr<double> psnr(uint64_t segment_bytes, size_t samples) const;
  // The PSNR CutEstimate gives the cut, after the whole stream is measured
  // with kRateControlSamples (at the first call); the same as psnr() for
  // the whole stream. Measured instead for a cut whose mesh differs from
  // the whole stream's.
  StatusOr<double> estimated_psnr(uint64_t segment_bytes) const;
  // The most segment bytes whose file fits in `bytes` (truncate_srm_to_size:
  // the table shrinks with the segments it lists, so this is a search, not a
  // subtraction). An error when even the smallest file takes more.
  StatusOr<uint64_t> segment_bytes_within(uint64_t bytes) const;

 private:
  const TriangleMesh& input_;
  const std::vector<uint8_t>& full_;
  uint64_t segment_bytes_ = 0;
  // The input's samples and search for `samples`, built at the first cut
  // measured and kept while the sample count stays the same: every cut is
  // measured against the same input. Shared, so that a cut still measuring
  // keeps the one it started with.
  StatusOr<std::shared_ptr<const SurfaceReference>> reference(size_t samples) const;
  StatusOr<TriangleMesh> decoded(uint64_t segment_bytes) const;
  // The metric's figures of the cut; its mesh into `mesh_out` when given.
  StatusOr<SurfaceDistance> measure(uint64_t segment_bytes, size_t samples, TriangleMesh* mesh_out = nullptr) const;
  mutable std::mutex reference_mutex_;
  mutable std::shared_ptr<const SurfaceReference> reference_;
  // Built at the first estimate: the whole stream decoded and measured.
  StatusOr<std::shared_ptr<const CutEstimate>> estimate() const;
  mutable std::mutex estimate_mutex_;
  mutable std::shared_ptr<const CutEstimate> estimate_;
};

// Samples per surface of the PSNR figures rate control measures: fewer than
// a final figure's.
inline constexpr size_t kRateControlSamples = 60000;

// With no rate option, `srcodec encode` keeps the knee of the stream's
// rate-distortion curve (knee_of_stream): past it, each further bit per
// input vertex gains less than kKneeDbPerBpv dB. There the stream's own curve
// flattens toward the remesh's error, its floor, while a coder that keeps
// the input's connectivity (Draco gains about 6 dB for each 1 to 3 more bits
// per input vertex) climbs on: bytes past the knee buy little. The figures
// behind this choice are in docs/codec_design.md, "The default rate".
inline constexpr double kKneeDbPerBpv = 1.0;
// The cuts judged on the way: each file this much larger than the last.
inline constexpr double kKneeCutRatio = 1.25;

// The PSNR of the whole stream, measured with kRateControlSamples.
StatusOr<double> whole_stream_psnr(const StreamCutter& cutter);

// The fewest segment bytes whose PSNR reaches `target` (bisection: the
// embedded stream's distortion does not grow with its length), measured with
// kRateControlSamples: the cut's bytes follow the metric's PSNR to a 2000th
// of the stream, closer than the estimate's tenths of a dB would place it.
StatusOr<uint64_t> segment_bytes_for_psnr(const StreamCutter& cutter, double target);

// Where knee_of_stream stopped: the segment bytes it keeps, that file's size
// and measured PSNR, and how many cuts it estimated and measured.
struct Knee {
  uint64_t segment_bytes = 0;
  uint64_t file_bytes = 0;
  double psnr = 0.0;
  int cuts = 0;               // cuts measured with the metric
  int estimated_cuts = 0;     // cuts placed and estimated
  bool whole_stream = false;  // no step gained less than kKneeDbPerBpv
};

// The knee search's ladder: the cut after `last`, whose file is
// kKneeCutRatio times as large (and keeps at least one segment byte more),
// or the smallest file when `last` is null; its PSNR left 0.
StatusOr<Knee> next_ladder_cut(const StreamCutter& cutter, const Knee* last);

// The PSNR gain (dB) the knee asks of the step from cut `from` to cut `to`:
// kKneeDbPerBpv for each bit per input vertex the step adds.
double knee_gain_needed(const Knee& from, const Knee& to, size_t input_vertices);

// How far above the gain a step needs the estimate must put it for the
// step to pass unmeasured (dB over two steps). Over the corpus the
// estimate's two-step gains are off the metric's by up to 1.2 dB, mostly
// under 0.5 (docs/codec_design.md, "How the knee is found").
inline constexpr double kKneeEstimateMargin = 1.5;

// From the smallest file (header, base mesh, flags) up, cuts whose files
// grow by kKneeCutRatio; keeps the first cut from which the next two steps
// gain less than kKneeDbPerBpv dB per bit per input vertex (of
// `input_vertices`), or the whole stream. A cut whose two steps the
// estimate puts more than kKneeEstimateMargin above that passes on the
// estimate; the others are decided by the metric (kRateControlSamples).
// Deterministic.
StatusOr<Knee> knee_of_stream(const StreamCutter& cutter, size_t input_vertices);

}  // namespace srcodec
