#include "codec/rate_control.h"

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

StatusOr<TriangleMesh> StreamCutter::decoded(uint64_t segment_bytes) const {
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cut(segment_bytes));
  SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(file.data(), file.size()));
  SRCODEC_ASSIGN_OR_RETURN(DecodedSrm d, decode_srm(f));
  return std::move(d.mesh);
}

StatusOr<SurfaceDistance> StreamCutter::measure(uint64_t segment_bytes, size_t samples, TriangleMesh* mesh_out) const {
  // Both serial: the input's reference, when it is still to build, is built
  // on the other core meanwhile.
  std::optional<StatusOr<TriangleMesh>> mesh;
  std::optional<StatusOr<std::shared_ptr<const SurfaceReference>>> ref;
  tbb::parallel_invoke([&] { mesh = decoded(segment_bytes); }, [&] { ref = reference(samples); });
  if (!mesh->ok()) return mesh->status();
  if (!ref->ok()) return ref->status();
  StatusOr<SurfaceDistance> s = ref->value()->distance_to(mesh->value());
  if (mesh_out) *mesh_out = std::move(mesh->value());
  return s;
}

StatusOr<double> StreamCutter::psnr(uint64_t segment_bytes, size_t samples) const {
  SRCODEC_ASSIGN_OR_RETURN(SurfaceDistance s, measure(segment_bytes, samples));
  return s.psnr;
}

StatusOr<std::shared_ptr<const CutEstimate>> StreamCutter::estimate() const {
  const std::lock_guard<std::mutex> lock(estimate_mutex_);
  if (!estimate_) {
    // Isolated, as in reference(): the measure's tasks must not take up a
    // task that waits for this lock.
    TriangleMesh mesh;
    StatusOr<SurfaceDistance> whole =
        tbb::this_task_arena::isolate([&] { return measure(segment_bytes_, kRateControlSamples, &mesh); });
    if (!whole.ok()) return whole.status();
    estimate_ = std::make_shared<const CutEstimate>(mesh, whole.value());
  }
  return estimate_;
}

StatusOr<double> StreamCutter::estimated_psnr(uint64_t segment_bytes) const {
  SRCODEC_ASSIGN_OR_RETURN(std::shared_ptr<const CutEstimate> e, estimate());
  if (segment_bytes >= segment_bytes_) return e->whole_psnr();
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh mesh, decoded(segment_bytes));
  StatusOr<double> estimated = e->psnr(mesh);
  if (estimated.ok()) return estimated;
  return psnr(segment_bytes, kRateControlSamples);
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

StatusOr<Knee> next_ladder_cut(const StreamCutter& cutter, const Knee* last) {
  Knee c;
  if (last) {
    const auto budget = static_cast<uint64_t>(std::ceil(static_cast<double>(last->file_bytes) * kKneeCutRatio));
    SRCODEC_ASSIGN_OR_RETURN(uint64_t within, cutter.segment_bytes_within(budget));
    c.segment_bytes = std::max(within, last->segment_bytes + 1);
  }
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cutter.cut(c.segment_bytes));
  c.file_bytes = file.size();
  return c;
}

double knee_gain_needed(const Knee& from, const Knee& to, size_t input_vertices) {
  return kKneeDbPerBpv * (8.0 / static_cast<double>(input_vertices)) *
         (static_cast<double>(to.file_bytes) - static_cast<double>(from.file_bytes));
}

namespace {

// The ladder of cuts knee_of_stream walks, each file kKneeCutRatio times
// the last, from the smallest file to the whole stream, placed as the walk
// needs them, with their PSNRs estimated and measured as it asks.
class KneeLadder {
 public:
  explicit KneeLadder(const StreamCutter& cutter) : cutter_(cutter) {}

  size_t size() const { return cuts_.size(); }
  const Knee& operator[](size_t k) const { return cuts_[k]; }
  bool complete() const { return !cuts_.empty() && cuts_.back().segment_bytes >= cutter_.segment_bytes(); }
  int measured_count() const { return measured_count_; }
  double estimated(size_t k) const { return estimated_[k]; }
  double measured(size_t k) const { return measured_[k]; }

  // Places cuts until there is one at index k or the ladder is complete:
  // where a cut lies depends only on the sizes of the files before it.
  Status place_to(size_t k) {
    while (cuts_.size() <= k && !complete()) {
      SRCODEC_ASSIGN_OR_RETURN(Knee c, next_ladder_cut(cutter_, cuts_.empty() ? nullptr : &cuts_.back()));
      cuts_.push_back(c);
      estimated_.push_back(kUnknown);
      measured_.push_back(kUnknown);
    }
    return ok_status();
  }

  // Cut k kept: its measured PSNR, and the counts of the search.
  Knee kept(size_t k) const {
    Knee at = cuts_[k];
    at.psnr = measured_[k];
    at.cuts = measured_count_;
    at.estimated_cuts = static_cast<int>(cuts_.size());
    return at;
  }

  // The PSNRs of cuts a and b (placed) where still unknown, both at once: a
  // cut's decode, and its measure's tree build, leave a core idle.
  Status estimate(size_t a, size_t b) {
    return fill(a, b, estimated_, [&](uint64_t s) { return cutter_.estimated_psnr(s); });
  }
  Status measure(size_t a, size_t b) {
    measured_count_ += (measured_[a] == kUnknown) + (b != a && measured_[b] == kUnknown);
    return fill(a, b, measured_, [&](uint64_t s) { return cutter_.psnr(s, kRateControlSamples); });
  }

 private:
  static constexpr double kUnknown = -std::numeric_limits<double>::infinity();

  template <class PsnrOf>
  Status fill(size_t a, size_t b, std::vector<double>& psnr, const PsnrOf& psnr_of) {
    const bool do_a = psnr[a] == kUnknown, do_b = b != a && psnr[b] == kUnknown;
    std::optional<StatusOr<double>> at_a, at_b;
    tbb::parallel_invoke(
        [&] {
          if (do_a) at_a = psnr_of(cuts_[a].segment_bytes);
        },
        [&] {
          if (do_b) at_b = psnr_of(cuts_[b].segment_bytes);
        });
    if (at_a && !at_a->ok()) return at_a->status();
    if (at_b && !at_b->ok()) return at_b->status();
    if (at_a) psnr[a] = at_a->value();
    if (at_b) psnr[b] = at_b->value();
    return ok_status();
  }

  const StreamCutter& cutter_;
  std::vector<Knee> cuts_;
  std::vector<double> estimated_, measured_;
  int measured_count_ = 0;
};

}  // namespace

StatusOr<Knee> knee_of_stream(const StreamCutter& cutter, size_t input_vertices) {
  if (input_vertices == 0) return invalid_argument("rate control: the input has no vertices");
  KneeLadder ladder(cutter);
  // Each cut judged by the two steps after it (a file about 1.56 times as
  // large): the PSNR of an embedded stream climbs in stairs, as bit planes
  // and levels begin, and one step alone can fall on a flat stair.
  for (size_t k = 0;; ++k) {
    SRCODEC_RETURN_IF_ERROR(ladder.place_to(k + 2));
    const size_t ahead = std::min(k + 2, ladder.size() - 1);
    if (ahead == k) {  // the whole stream: no knee before it
      SRCODEC_RETURN_IF_ERROR(ladder.measure(k, k));
      Knee at = ladder.kept(k);
      at.whole_stream = true;
      return at;
    }
    const double needed = knee_gain_needed(ladder[k], ladder[ahead], input_vertices);
    // A gain the estimate puts clearly above what is needed passes unmeasured;
    // anywhere near it, or below, the metric decides.
    SRCODEC_RETURN_IF_ERROR(ladder.estimate(k, ahead));
    if (ladder.estimated(ahead) - ladder.estimated(k) >= needed + kKneeEstimateMargin) continue;
    SRCODEC_RETURN_IF_ERROR(ladder.measure(k, ahead));
    // An exact reproduction (infinite PSNR) gains more than any slope; a cut
    // already exact gains nothing more.
    if (!(ladder.measured(ahead) - ladder.measured(k) >= needed)) return ladder.kept(k);
  }
}

}  // namespace srcodec
