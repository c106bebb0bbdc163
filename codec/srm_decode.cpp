// The decoding half of the .srm codec (codec/srm_codec.h): base mesh, then
// the refinement flags replayed into the hierarchy, then the coefficients,
// scaled and inverse-lifted. On a large mesh a second core builds the
// wavelet plan while the coefficients decode, and the coarse levels are
// lifted while the finest level's coefficients are still being decoded.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <future>
#include <optional>

#include "codec/base_mesh_coder.h"
#include "codec/bitplane.h"
#include "codec/crease_coder.h"
#include "codec/flags_coder.h"
#include "codec/srm_codec.h"
#include "codec/srm_layout.h"
#include "format/in_halves.h"
#include "format/prefault.h"
#include "format/semi_regular/creases.h"
#include "wavelet/lifting.h"

namespace srcodec {
namespace {

// Below this much fresh hierarchy memory the decoder does not prefault it.
constexpr size_t kPrefaultMinBytes = size_t{4} << 20;
// From this many vertices on, the decoder scales the coefficients on two threads.
constexpr size_t kParallelScaleVertices = size_t{1} << 15;

// The vertices of levels 0 .. `level`, refused over `max_vertices` before
// anything is allocated (a tiny file can describe a huge mesh).
StatusOr<uint64_t> vertices_up_to(const SrmHeader& h, int level, uint64_t max_vertices) {
  // Saturating: the header's counts are untrusted varints of up to 64 bits.
  uint64_t total = 0;
  for (int j = 0; j <= level; ++j) total += std::min(h.level_vertices[j], UINT64_MAX - total);
  if (total > max_vertices)
    return invalid_argument("level " + std::to_string(level) + " has " + std::to_string(total) +
                            " vertices, over the limit of " + std::to_string(max_vertices));
  return total;
}

// A file cut inside its base mesh: the base triangles decoded before the cut
// (none while the chunk's counts are cut), at level 0. The chunk's checksum
// cannot be checked; the decoder still refuses what the bytes present get wrong.
StatusOr<DecodedSrm> decode_cut_base(const SrmFile& file) {
  const SrmHeader& h = file.header;
  StatusOr<DecodedBaseMesh> base = decode_base_mesh_prefix(file.base.bytes.data(), file.base.bytes.size(), grid_of(h),
                                                           h.base_vertices, h.base_triangles);
  if (!base.ok()) return base.status().with_context("base mesh at byte " + std::to_string(file.base.offset));
  DecodedSrm out;
  out.level = 0;
  out.base_vertices = h.base_vertices;
  out.base_cut = true;
  out.bytes_used = file.base.offset + file.base.bytes.size();
  out.mesh.positions = std::move(base->positions);
  out.mesh.triangles = std::move(base->triangles);
  return out;
}

// The whole base mesh chunk, checked against its checksum and the header.
StatusOr<DecodedBaseMesh> decode_whole_base(const SrmFile& file) {
  const SrmHeader& h = file.header;
  SRCODEC_RETURN_IF_ERROR(verify_chunk(file.base, false, "the base mesh"));
  StatusOr<DecodedBaseMesh> base = decode_base_mesh(file.base.bytes.data(), file.base.bytes.size(), grid_of(h),
                                                    h.base_vertices, h.base_triangles);
  if (!base.ok()) return base.status().with_context("base mesh at byte " + std::to_string(file.base.offset));
  if (base->positions.size() != h.base_vertices || base->triangles.size() != h.base_triangles)
    return parse_error("the base mesh has other counts than the header: the file is corrupt");
  return base;
}

// The whole crease chunk of the base mesh, checked against its checksum.
StatusOr<std::vector<std::array<int32_t, 2>>> decode_whole_creases(const SrmFile& file, const DecodedBaseMesh& base) {
  SRCODEC_RETURN_IF_ERROR(verify_chunk(file.creases, false, "the creases"));
  StatusOr<std::vector<std::array<int32_t, 2>>> creases =
      decode_creases(base.triangles, static_cast<int32_t>(base.positions.size()), file.creases.bytes.data(),
                     file.creases.bytes.size());
  if (!creases.ok()) return creases.status().with_context("creases at byte " + std::to_string(file.creases.offset));
  return creases;
}

// Replays the flags up to `level`; returns the level reached (lower when the
// file was cut inside a flag chunk).
StatusOr<int> decode_hierarchy(const SrmFile& file, int level, TriangleHierarchy& h, uint64_t max_vertices) {
  for (int j = 0; j < level; ++j) {
    const SrmChunk& c = file.flags[j];
    if (!c.complete()) return j;
    const std::string what = "the flags of level " + std::to_string(j);
    SRCODEC_RETURN_IF_ERROR(verify_chunk(c, false, what));
    SRCODEC_RETURN_IF_ERROR(decode_refinement_level(h, j, c.bytes.data(), c.bytes.size(), max_vertices));
    const uint64_t created = h.level_vertex_count(j + 1) - h.level_vertex_count(j);
    if (created != file.header.level_vertices[j + 1])
      return parse_error(what + " make " + std::to_string(created) + " vertices of level " + std::to_string(j + 1) +
                         ", the header says " + std::to_string(file.header.level_vertices[j + 1]) +
                         ": the file is corrupt");
  }
  return level;
}

// decode_hierarchy into memory reserved for the `total` vertices the header
// announces, which the other core maps meanwhile.
StatusOr<int> replay_refinement(const SrmFile& file, int level, uint64_t total, const SrmDecodeOptions& options,
                                TriangleHierarchy& hier) {
  const SrmHeader& h = file.header;
  // Every split makes 4 nodes and the midpoints of its 3 edges, each new
  // vertex the midpoint of at most 2 splits: splits <= 2/3 of the new
  // vertices, which a closed uniform hierarchy reaches. (Only a hint: `total`
  // is within the vertex limit, a corrupt count costs nothing.)
  const uint64_t new_vertices = total > h.base_vertices ? total - h.base_vertices : 0;
  hier.reserve(h.base_triangles + 4 * (2 * new_vertices / 3), total);
  // The replay writes those arrays for the first time: mapping their pages
  // on the other core saves a page fault per 4 KB here. The prefault stops
  // on return at the latest and changes no byte; a header that lies about
  // its counts makes it map at most what `max_vertices` allows.
  const BackgroundPrefault prefaulting(options.threads ? hier.reserved_memory() : std::vector<MemoryRange>{},
                                       kPrefaultMinBytes);
  return decode_hierarchy(file, level, hier, options.max_vertices);
}

// Where the header, the base mesh, the creases (when whole) and the flags of
// levels below `level` end.
uint64_t bytes_through_flags(const SrmFile& file, int level) {
  uint64_t end = file.base.offset + file.base.declared;
  if (file.creases.complete()) end = file.creases.offset + file.creases.declared;
  for (int j = 0; j < level; ++j) end = file.flags[j].offset + file.flags[j].declared;
  return end;
}

// The coefficient segments of levels <= `level` in stream order, up to the
// first one missing or cut; `bytes_used` grows to the end of the last byte
// taken.
StatusOr<std::vector<BitplaneSegmentView>> segment_views(const SrmFile& file, int level, uint64_t* bytes_used) {
  const SrmHeader& h = file.header;
  std::vector<BitplaneSegmentView> views;
  for (int p = h.top_plane; p >= 0; --p) {
    for (int f = 0; f <= level; ++f) {
      const size_t index = h.segment_index(p, f);
      if (index >= file.segments.size()) return views;  // the table ends: the encoder cut the stream here
      const SrmChunk& c = file.segments[index];
      SRCODEC_RETURN_IF_ERROR(verify_chunk(c, true, "segment (plane " + std::to_string(p) + ", level " +
                                                        std::to_string(f) + ")"));
      views.push_back({p, f + 1, c.bytes.data(), c.bytes.size()});
      if (!c.bytes.empty()) *bytes_used = std::max<uint64_t>(*bytes_used, c.offset + c.bytes.size());
      if (!c.complete()) return views;
    }
  }
  return views;
}

// The wavelet plan and the level's triangles: pure functions of the
// hierarchy, built on a second thread (with `threads`) while the
// coefficients decode. The triangles are listed by whichever thread gets to
// them first: the plan's after the plan, or the caller's.
class PlanJob {
 public:
  PlanJob(const TriangleHierarchy& hier, int level, const std::vector<std::array<int32_t, 2>>& creases, bool threads)
      : hier_(hier), level_(level), creases_(creases) {
    job_ = std::async(threads ? std::launch::async : std::launch::deferred, [this] {
      StatusOr<LiftingPlan> plan = LiftingPlan::build(hier_, level_, creases_);
      if (!claimed_.exchange(true)) triangles_ = hier_.level_triangles(level_);
      return plan;
    });
  }
  // The plan, waiting for it if need be (the job's future gives it once).
  const StatusOr<LiftingPlan>& plan() {
    if (!plan_) plan_.emplace(job_.get());
    return *plan_;
  }
  std::vector<std::array<int32_t, 3>> take_triangles() {
    if (!claimed_.exchange(true)) triangles_ = hier_.level_triangles(level_);
    plan();  // the job may still be listing them
    return std::move(triangles_);
  }

 private:
  const TriangleHierarchy& hier_;
  const int level_;
  const std::vector<std::array<int32_t, 2>>& creases_;
  std::atomic<bool> claimed_{false};
  std::vector<std::array<int32_t, 3>> triangles_;
  std::future<StatusOr<LiftingPlan>> job_;
  std::optional<StatusOr<LiftingPlan>> plan_;
};

// The decoded coefficient values scaled into base positions and details,
// then inverse-lifted into the level's positions.
class Reconstruction {
 public:
  Reconstruction(const TriangleHierarchy& hier, const ForestLayout& layout, const SrmHeader& h,
                 const DecodedBaseMesh& base, int level, PlanJob& plan)
      : hier_(hier), layout_(layout), steps_(step_table(h)), base_(base), level_(level), plan_(plan),
        base_positions_(base.positions), detail_(hier.vertex_count()) {
    // The forest holds every vertex of the replayed hierarchy once (its
    // levels are all <= `level`), so every detail is written by scale(), zero
    // or not, and the array need not be cleared first (Eigen leaves it
    // uninitialized). Base vertices' slots get zeros.
    if (layout.vertex.size() != detail_.size()) std::fill(detail_.begin(), detail_.end(), Eigen::Vector3d::Zero());
  }

  // The decode_bitplane_values callback: while the finest level's
  // coefficients are still being decoded on the other core, the coarser
  // levels' (which come first in the forest) are scaled and lifted here;
  // inverse lifting works level by level, so the finest level's step is all
  // that is left after. Redone from scratch if the decode starts over
  // (corrupt input only).
  void lift_coarse_levels(const BitplaneValueView& coarse) {
    coarse_vertices_ = coarse.size() / kSrmComponents;
    scale(coarse, 0, coarse_vertices_);
    const StatusOr<LiftingPlan>& p = plan_.plan();
    if (!p.ok() || !p->covers_every_vertex(level_)) return;
    inverse_lifting_in_place(p.value(), base_positions_, detail_, 1, level_ - 1, false);
    coarse_lifted_ = true;
  }

  // The level's positions from all the values; `coarse_final`: the values
  // lift_coarse_levels saw are these (BitplaneDecodeStats::coarse_done_final).
  StatusOr<std::vector<Eigen::Vector3d>> finish(const BitplaneValues& values, bool coarse_final, bool threads) {
    const bool staged = coarse_lifted_ && coarse_final;
    // The rest of the vertices (all of them unless staged); on a big mesh,
    // half of it on the other core (which also spreads the page faults).
    const size_t first = staged ? coarse_vertices_ : 0, vertices = layout_.vertex.size();
    const BitplaneValueView all = values.view();
    run_in_halves(first, vertices, threads && vertices - first >= kParallelScaleVertices,
                  [&](size_t begin, size_t end) { scale(all, begin, end); });
    const StatusOr<LiftingPlan>& lifting = plan_.plan();
    if (!lifting.ok()) return lifting.status().with_context("wavelet plan");
    if (staged) {
      inverse_lifting_in_place(lifting.value(), base_positions_, detail_, level_, level_, threads);
      return std::move(detail_);
    }
    return inverse_lifting(lifting.value(), base_positions_, std::move(detail_), level_, threads);
  }

 private:
  // The values of the vertices layout.vertex[from .. to) into their details,
  // or base positions (again from the decoded base: nothing is carried over
  // when this is redone).
  void scale(const BitplaneValueView& values, size_t from, size_t to) {
    for (size_t k = from; k < to; ++k) {
      const int32_t v = layout_.vertex[k];
      const int f = hier_.vertex_level(v);
      const double* step = &steps_[f * kSrmComponents];
      const size_t node = k * kSrmComponents;
      Eigen::Vector3d& d = detail_[v];
      for (int c = 0; c < kSrmComponents; ++c) d[c] = values.value(node + c) * step[c];
      if (f == 0) {
        base_positions_[v] = base_.positions[v] + d;
        d.setZero();
      }
    }
  }

  const TriangleHierarchy& hier_;
  const ForestLayout& layout_;
  const std::vector<double> steps_;
  const DecodedBaseMesh& base_;
  const int level_;
  PlanJob& plan_;
  std::vector<Eigen::Vector3d> base_positions_;
  std::vector<Eigen::Vector3d> detail_;
  size_t coarse_vertices_ = 0;
  bool coarse_lifted_ = false;
};

}  // namespace

StatusOr<std::vector<std::array<int32_t, 2>>> decode_srm_creases(const SrmFile& file) {
  if (!file.header.has_creases) return std::vector<std::array<int32_t, 2>>{};
  SRCODEC_ASSIGN_OR_RETURN(const DecodedBaseMesh base, decode_whole_base(file));
  return decode_whole_creases(file, base);
}

StatusOr<DecodedSrm> decode_srm(const SrmFile& file, const SrmDecodeOptions& options) {
  const SrmHeader& h = file.header;
  int level = options.level < 0 ? h.levels : std::min(options.level, h.levels);
  SRCODEC_ASSIGN_OR_RETURN(const uint64_t total, vertices_up_to(h, level, options.max_vertices));
  if (!file.base.complete()) return decode_cut_base(file);
  SRCODEC_ASSIGN_OR_RETURN(const DecodedBaseMesh base, decode_whole_base(file));
  // Every level above the base follows the creases: without all of them,
  // the base mesh is what the bytes give (as with a cut base mesh).
  std::vector<std::array<int32_t, 2>> creases;
  const bool creases_cut = h.has_creases && !file.creases.complete();
  if (creases_cut) level = 0;
  if (h.has_creases && !creases_cut) {
    SRCODEC_ASSIGN_OR_RETURN(creases, decode_whole_creases(file, base));
  }
  StatusOr<TriangleHierarchy> created =
      TriangleHierarchy::create(static_cast<int32_t>(h.base_vertices), base.triangles);
  if (!created.ok()) return created.status().with_context("the base mesh is not valid");
  TriangleHierarchy& hier = created.value();
  SRCODEC_ASSIGN_OR_RETURN(level, replay_refinement(file, level, total, options, hier));

  DecodedSrm out;
  out.level = level;
  out.base_vertices = h.base_vertices;
  out.bytes_used = bytes_through_flags(file, level);
  out.creases_cut = creases_cut;
  PlanJob plan(hier, level, creases, options.threads);
  const ForestLayout layout = build_forest(hier, level);
  SRCODEC_ASSIGN_OR_RETURN(const std::vector<BitplaneSegmentView> views, segment_views(file, level, &out.bytes_used));
  Reconstruction reconstruction(hier, layout, h, base, level, plan);
  BitplaneDecodeStats stats;
  StatusOr<BitplaneValues> values = decode_bitplane_values(
      layout.forest, h.top_plane, views, level + 1, &stats,
      options.threads ? BitplaneThreads::kAuto : BitplaneThreads::kSequential, h.raw_planes,
      [&](const BitplaneValueView& coarse) { reconstruction.lift_coarse_levels(coarse); });
  if (!values.ok()) return values.status().with_context("coefficients");
  out.last_plane = stats.last_complete_plane > h.top_plane ? -1 : stats.last_complete_plane;
  SRCODEC_ASSIGN_OR_RETURN(out.mesh.positions,
                           reconstruction.finish(values.value(), stats.coarse_done_final, options.threads));
  // Every vertex of the replayed hierarchy (levels <= `level`) is a corner
  // of some triangle of the level mesh: the mesh is already compact.
  out.mesh.triangles = plan.take_triangles();
  out.crease_edges = crease_edges_up_to(hier, creases, level);
  return out;
}

}  // namespace srcodec
