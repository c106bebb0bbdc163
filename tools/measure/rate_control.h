// Rate control over an embedded .srm stream: which prefix of its
// coefficient segments to keep for a byte budget or a PSNR target, measured
// with the project's metric against the input. Used by `srcodec encode` and
// the speed benchmark.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

// The file that keeps the first `segment_bytes` bytes of coefficient
// segments (truncate_srm), its size, and the PSNR against the input of the
// mesh it decodes to. Holds references: `input` and `full` must outlive it.
class StreamCutter {
 public:
  StreamCutter(const TriangleMesh& input, const std::vector<uint8_t>& full);
  uint64_t segment_bytes() const { return segment_bytes_; }
  StatusOr<std::vector<uint8_t>> cut(uint64_t segment_bytes) const;
  StatusOr<double> psnr(uint64_t segment_bytes, size_t samples) const;
  // The most segment bytes whose file fits in `bytes` (the table shrinks
  // with the segments it lists, so this is a search, not a subtraction).
  StatusOr<uint64_t> segment_bytes_within(uint64_t bytes) const;

 private:
  const TriangleMesh& input_;
  const std::vector<uint8_t>& full_;
  uint64_t segment_bytes_ = 0;
};

// Samples per surface of the PSNR figures rate control decides on: fewer
// than a final figure's.
inline constexpr size_t kRateControlSamples = 60000;

// With no rate option, `srcodec encode` aims this many dB below the PSNR of
// the whole stream (whole_stream_psnr).
inline constexpr double kDefaultDbBelowWholeStream = 1.0;

// The PSNR of the whole stream, with kRateControlSamples.
StatusOr<double> whole_stream_psnr(const StreamCutter& cutter);

// The fewest segment bytes whose PSNR reaches `target` (bisection: the
// embedded stream's distortion does not grow with its length), measured with
// kRateControlSamples.
StatusOr<uint64_t> segment_bytes_for_psnr(const StreamCutter& cutter, double target);

}  // namespace srcodec
