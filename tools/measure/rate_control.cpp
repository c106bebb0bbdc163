#include "tools/measure/rate_control.h"

#include <algorithm>

#include "codec/srm_codec.h"
#include "format/srm_file.h"
#include "tools/measure/surface_distance.h"

namespace srcodec {

StreamCutter::StreamCutter(const TriangleMesh& input, const std::vector<uint8_t>& full) : input_(input), full_(full) {
  const StatusOr<SrmFile> f = parse_srm(full.data(), full.size());
  if (f.ok())
    for (const SrmChunk& c : f->segments) segment_bytes_ += c.declared;
}

StatusOr<std::vector<uint8_t>> StreamCutter::cut(uint64_t segment_bytes) const {
  return truncate_srm(full_, segment_bytes);
}

StatusOr<double> StreamCutter::psnr(uint64_t segment_bytes, size_t samples) const {
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cut(segment_bytes));
  SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(file.data(), file.size()));
  SRCODEC_ASSIGN_OR_RETURN(DecodedSrm d, decode_srm(f));
  SurfaceDistanceOptions o;
  o.samples_per_surface = samples;
  SRCODEC_ASSIGN_OR_RETURN(SurfaceDistance s, surface_distance(input_, d.mesh, o));
  return s.psnr;
}

StatusOr<uint64_t> StreamCutter::segment_bytes_within(uint64_t bytes) const {
  uint64_t lo = 0, hi = segment_bytes_;
  while (lo < hi) {
    const uint64_t mid = lo + (hi - lo + 1) / 2;
    SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cut(mid));
    if (file.size() <= bytes) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return lo;
}

StatusOr<double> whole_stream_psnr(const StreamCutter& cutter) {
  return cutter.psnr(cutter.segment_bytes(), kRateControlSamples);
}

StatusOr<uint64_t> segment_bytes_for_psnr(const StreamCutter& cutter, double target) {
  uint64_t lo = 0, hi = cutter.segment_bytes();
  SRCODEC_ASSIGN_OR_RETURN(double at_lo, cutter.psnr(lo, kRateControlSamples));
  if (at_lo >= target) return lo;
  while (hi - lo > std::max<uint64_t>(8, hi / 2000)) {
    const uint64_t mid = lo + (hi - lo) / 2;
    SRCODEC_ASSIGN_OR_RETURN(double p, cutter.psnr(mid, kRateControlSamples));
    (p >= target ? hi : lo) = mid;
  }
  return hi;
}

}  // namespace srcodec
