#include "codec/rate_control.h"

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "codec/srm_codec.h"
#include "format/srm/srm_file.h"

namespace srcodec {

StreamCutter::StreamCutter(const TriangleMesh& input, const std::vector<uint8_t>& full) : input_(input), full_(full) {
  const StatusOr<SrmFile> f = parse_srm(full.data(), full.size());
  if (f.ok())
    for (const SrmChunk& c : f->segments) segment_bytes_ += c.declared;
}

StatusOr<std::vector<uint8_t>> StreamCutter::cut(uint64_t segment_bytes) const {
  return truncate_srm(full_, segment_bytes);
}

StatusOr<std::shared_ptr<const SurfaceReference>> StreamCutter::reference(size_t samples) const {
  const std::lock_guard<std::mutex> lock(reference_mutex_);
  if (!reference_ || reference_->samples_per_surface() != samples) {
    SurfaceDistanceOptions o;
    o.samples_per_surface = samples;
    // Isolated: a thread waiting for the build's own tasks could otherwise
    // take up another cut's task, which asks for this lock again.
    StatusOr<SurfaceReference> built =
        tbb::this_task_arena::isolate([&] { return SurfaceReference::build(input_, o); });
    if (!built.ok()) return built.status();
    reference_ = std::make_shared<const SurfaceReference>(std::move(built).value());
  }
  return reference_;
}

StatusOr<double> StreamCutter::psnr(uint64_t segment_bytes, size_t samples) const {
  const auto decode_cut = [&]() -> StatusOr<DecodedSrm> {
    SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cut(segment_bytes));
    SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(file.data(), file.size()));
    return decode_srm(f);
  };
  // Both serial: the input's reference, when it is still to build, is built
  // on the other core meanwhile.
  std::optional<StatusOr<DecodedSrm>> decoded;
  std::optional<StatusOr<std::shared_ptr<const SurfaceReference>>> ref;
  tbb::parallel_invoke([&] { decoded = decode_cut(); }, [&] { ref = reference(samples); });
  if (!decoded->ok()) return decoded->status();
  if (!ref->ok()) return ref->status();
  SRCODEC_ASSIGN_OR_RETURN(SurfaceDistance s, ref->value()->distance_to(decoded->value().mesh));
  return s.psnr;
}

StatusOr<uint64_t> StreamCutter::segment_bytes_within(uint64_t bytes) const {
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, truncate_srm_to_size(full_.data(), full_.size(), bytes));
  SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(file.data(), file.size()));
  uint64_t kept = 0;
  for (const SrmChunk& c : f.segments) kept += c.bytes.size();
  return kept;
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

StatusOr<Knee> knee_of_stream(const StreamCutter& cutter, size_t input_vertices) {
  if (input_vertices == 0) return invalid_argument("rate control: the input has no vertices");
  const double bits_per_byte_vertex = 8.0 / static_cast<double>(input_vertices);
  // The cut keeping `segment_bytes`, or after `last` (each file
  // kKneeCutRatio times the last): its file's size, its PSNR still 0.
  const auto place = [&](const Knee* last) -> StatusOr<Knee> {
    Knee c;
    if (last) {
      const auto budget = static_cast<uint64_t>(std::ceil(static_cast<double>(last->file_bytes) * kKneeCutRatio));
      SRCODEC_ASSIGN_OR_RETURN(uint64_t within, cutter.segment_bytes_within(budget));
      c.segment_bytes = std::max(within, last->segment_bytes + 1);
    }
    SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cutter.cut(c.segment_bytes));
    c.file_bytes = file.size();
    return c;
  };
  // The PSNR of a placed cut.
  const auto measured = [&](StatusOr<Knee> c) -> StatusOr<Knee> {
    if (!c.ok()) return c;
    SRCODEC_ASSIGN_OR_RETURN(c.value().psnr, cutter.psnr(c.value().segment_bytes, kRateControlSamples));
    return c;
  };
  std::vector<Knee> cuts;  // every cut measured, each file kKneeCutRatio times the last
  // A cut measured ahead that failed: the error once the ladder needs it.
  Status failed_ahead = ok_status();
  // The next two cuts (one when the next is the whole stream), measured at
  // once: where a cut lies depends on the sizes of the files before it, not
  // on their PSNRs, and a cut's decode and tree build leave a core idle.
  const auto measure_next = [&]() -> Status {
    SRCODEC_RETURN_IF_ERROR(failed_ahead);
    SRCODEC_ASSIGN_OR_RETURN(const Knee first, place(cuts.empty() ? nullptr : &cuts.back()));
    std::optional<StatusOr<Knee>> one, two;
    tbb::parallel_invoke([&] { one = measured(first); },
                         [&] {
                           if (first.segment_bytes < cutter.segment_bytes()) two = measured(place(&first));
                         });
    if (!one->ok()) return one->status();
    cuts.push_back(one->value());
    if (two && two->ok()) cuts.push_back(two->value());
    if (two && !two->ok()) failed_ahead = two->status();
    return ok_status();
  };
  // Each cut judged by the two steps after it (a file about 1.56 times as
  // large): the PSNR of an embedded stream climbs in stairs, as bit planes
  // and levels begin, and one step alone can fall on a flat stair.
  for (size_t k = 0;; ++k) {
    while (cuts.size() < k + 3 && (cuts.empty() || cuts.back().segment_bytes < cutter.segment_bytes()))
      SRCODEC_RETURN_IF_ERROR(measure_next());
    const size_t ahead = std::min(k + 2, cuts.size() - 1);
    Knee at = cuts[k];
    at.cuts = static_cast<int>(cuts.size());
    if (ahead == k) {  // the whole stream: no knee before it
      at.whole_stream = true;
      return at;
    }
    const double bpv_gained = bits_per_byte_vertex * (static_cast<double>(cuts[ahead].file_bytes) -
                                                      static_cast<double>(at.file_bytes));
    // An exact reproduction (infinite PSNR) gains more than any slope; a cut
    // already exact gains nothing more.
    if (!(cuts[ahead].psnr - at.psnr >= kKneeDbPerBpv * bpv_gained)) return at;
  }
}

}  // namespace srcodec
