#include "codec/srm_codec.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <future>
#include <optional>

#include "codec/base_mesh_coder.h"
#include "codec/bitplane.h"
#include "codec/flags_coder.h"
#include "format/in_halves.h"
#include "format/prefault.h"
#include "wavelet/lifting.h"

namespace srcodec {
namespace {

constexpr int32_t kMaxQuantized = (1 << kSrmMaxPlane) - 1;

// Below this much fresh hierarchy memory the decoder does not prefault it.
constexpr size_t kPrefaultMinBytes = size_t{4} << 20;
// From this many vertices on, the decoder scales the coefficients on two threads.
constexpr size_t kParallelScaleVertices = size_t{1} << 15;

// The coefficient forest of a hierarchy up to `levels`: three nodes (one per
// component) per base vertex (f = 0, the base residual), then per vertex of
// level 1, 2, ... in id order. The tree parent of a level-j vertex (j >= 2)
// is the endpoint of its parent edge with the higher level (the newer one,
// always of level j - 1), ties to the higher id; level-1 vertices are roots.
struct ForestLayout {
  CoefficientForest forest;
  std::vector<int32_t> vertex;   // per node / 3: the hierarchy vertex
  std::vector<int32_t> first_node;  // per hierarchy vertex: its x node, -1 when above `levels`
};

ForestLayout build_forest(const TriangleHierarchy& h, int levels) {
  ForestLayout out;
  const int32_t vertex_count = h.vertex_count();
  // The vertices of levels 0 .. `levels`, by level, each level in id order.
  // A decoder's replay numbers them so already (level by level): then they
  // are just listed; a remesher's adaptive hierarchy need not, and gets a
  // counting sort.
  std::vector<size_t> level_begin(levels + 2, 0);
  bool sorted = true;
  int32_t previous = 0;
  for (int32_t v = 0; v < vertex_count; ++v) {
    const int32_t l = h.vertex_level(v);
    if (l > levels) continue;
    ++level_begin[l + 1];
    sorted = sorted && l >= previous;
    previous = l;
  }
  for (int f = 0; f <= levels; ++f) level_begin[f + 1] += level_begin[f];
  out.vertex.resize(level_begin[levels + 1]);
  {
    std::vector<size_t> fill(level_begin.begin(), level_begin.end() - 1);
    size_t k = 0;
    for (int32_t v = 0; v < vertex_count; ++v) {
      const int32_t l = h.vertex_level(v);
      if (l <= levels) out.vertex[sorted ? k++ : fill[l]++] = v;
    }
  }
  const size_t nodes = out.vertex.size() * kSrmComponents;
  // Written through pointers: push_back's capacity checks cost more than the
  // work on the decoder's path.
  out.forest.parent.resize(nodes);
  out.forest.level.resize(nodes);
  out.forest.context_class.resize(nodes);
  out.first_node.assign(vertex_count, -1);
  int32_t* parent_of = out.forest.parent.data();
  uint8_t* level_of = out.forest.level.data();
  uint8_t* class_of = out.forest.context_class.data();
  for (size_t k = 0; k < out.vertex.size(); ++k) {
    const int32_t v = out.vertex[k];
    const int32_t f = h.vertex_level(v);
    int32_t parent = -1;
    if (f >= 2) {
      const auto e = h.parent_edge(v);
      const int32_t la = h.vertex_level(e[0]), lb = h.vertex_level(e[1]);
      const int32_t p = (la != lb) ? (la > lb ? e[0] : e[1]) : std::max(e[0], e[1]);
      parent = out.first_node[p];
    }
    const size_t first = k * kSrmComponents;
    out.first_node[v] = static_cast<int32_t>(first);
    for (int c = 0; c < kSrmComponents; ++c) {
      parent_of[first + c] = parent < 0 ? -1 : parent + c;
      level_of[first + c] = static_cast<uint8_t>(f + 1);
      class_of[first + c] = static_cast<uint8_t>(f * kSrmComponents + c);
    }
  }
  return out;
}

// quant_step x scale(f, c) for every (f, c), at index 3f + c.
std::vector<double> step_table(const SrmHeader& h) {
  std::vector<double> steps;
  for (int f = 0; f <= h.levels; ++f)
    for (int c = 0; c < kSrmComponents; ++c) steps.push_back(h.quant_step * h.scale(f, c));
  return steps;
}

// What the header stores as f32, rounded the same way on both sides.
double as_float(double v) { return static_cast<double>(static_cast<float>(v)); }

QuantizationGrid grid_of(const SrmHeader& h) {
  QuantizationGrid g;
  g.origin = h.bbox_min;
  g.step = h.grid_step;
  g.bits = h.base_bits;
  return g;
}

double component(const Eigen::Vector3d& v, int c) { return v[c]; }

}  // namespace

StatusOr<EncodedSrm> encode_srm(const SemiRegularMesh& mesh, const TriangleMesh& input, const SrmEncodeOptions& options) {
  if (input.positions.empty()) return invalid_argument("encode: the input mesh has no vertices");
  if (!(options.step_fraction > 0.0) || !(options.tangential_factor > 0.0))
    return invalid_argument("encode: the quantizer step and tangential factor must be positive");
  if (options.base_bits < 4 || options.base_bits > 24)
    return invalid_argument("encode: base position bits must be 4..24");
  if (options.raw_planes < 0 || options.raw_planes > kSrmMaxPlane + 1)
    return invalid_argument("encode: raw planes must be 0.." + std::to_string(kSrmMaxPlane + 1));
  const int levels = mesh.levels;
  if (levels < 0 || levels > kSrmMaxLevels)
    return invalid_argument("encode: " + std::to_string(levels) + " levels; the format holds 0.." +
                            std::to_string(kSrmMaxLevels));
  SrmHeader h;
  h.input_vertices = input.positions.size();
  h.input_triangles = input.triangles.size();
  h.bbox_min = h.bbox_max = input.positions[0];
  for (const auto& p : input.positions) {
    h.bbox_min = h.bbox_min.cwiseMin(p);
    h.bbox_max = h.bbox_max.cwiseMax(p);
  }
  h.bbox_min = h.bbox_min.unaryExpr(&as_float);
  h.bbox_max = h.bbox_max.unaryExpr(&as_float);
  const double extent = (h.bbox_max - h.bbox_min).maxCoeff();
  const double diagonal = (h.bbox_max - h.bbox_min).norm();
  h.levels = levels;
  h.base_bits = options.base_bits;
  h.grid_step = as_float(extent > 0 ? extent / ((1 << options.base_bits) - 1) : 1.0);
  h.quant_step = as_float(diagonal > 0 ? diagonal * options.step_fraction : options.step_fraction);
  h.tangential_factor = as_float(options.tangential_factor);
  h.raw_planes = options.raw_planes;

  const int32_t nbase = mesh.hierarchy.base_vertex_count();
  // The base mesh carries the level-0 approximation (base vertices after the
  // update steps), not the base vertices' own positions: the transform on the
  // remesher's numbering gives it before the replay renumbers everything.
  StatusOr<LiftingPlan> original_plan = LiftingPlan::build(mesh.hierarchy, levels);
  if (!original_plan.ok()) return original_plan.status().with_context("encode: wavelet plan");
  const std::vector<Eigen::Vector3d> approximation = forward_lifting(original_plan.value(), mesh.positions).base;
  StatusOr<BaseMeshCode> base = encode_base_mesh(approximation, mesh.base.triangles, grid_of(h));
  if (!base.ok()) return base.status().with_context("encode: base mesh");
  StatusOr<ReplayedHierarchy> replay = encode_refinement(mesh.hierarchy, levels, base->triangles,
                                                         base->new_to_old_vertex, base->new_to_old_triangle);
  if (!replay.ok()) return replay.status().with_context("encode");
  const TriangleHierarchy& hier = replay->hierarchy;
  h.base_vertices = nbase;
  h.base_triangles = base->triangles.size();
  h.level_vertices.assign(levels + 1, 0);
  for (int32_t v = 0; v < hier.vertex_count(); ++v) ++h.level_vertices[hier.vertex_level(v)];

  std::vector<Eigen::Vector3d> positions(hier.vertex_count());
  for (int32_t v = 0; v < hier.vertex_count(); ++v) positions[v] = mesh.positions[replay->to_original_vertex[v]];
  StatusOr<LiftingPlan> plan = LiftingPlan::build(hier, levels);
  if (!plan.ok()) return plan.status().with_context("encode: wavelet plan");
  const WaveletCoefficients coeffs = forward_lifting(plan.value(), positions);

  const ForestLayout layout = build_forest(hier, levels);
  const std::vector<double> steps = step_table(h);
  std::vector<int32_t> q(layout.forest.parent.size());
  for (size_t node = 0; node < q.size(); ++node) {
    const int32_t v = layout.vertex[node / kSrmComponents];
    const int c = static_cast<int>(node % kSrmComponents);
    const int f = hier.vertex_level(v);
    const double value = f == 0 ? component(coeffs.base[v] - base->positions[v], c) : component(coeffs.detail[v], c);
    const double units = std::abs(value) / steps[f * kSrmComponents + c];
    const int32_t m = static_cast<int32_t>(std::min<double>(std::floor(units), kMaxQuantized));
    q[node] = value < 0 ? -m : m;
  }
  const BitplaneStream stream = encode_bitplanes(layout.forest, q, h.raw_planes);
  h.top_plane = stream.top_plane;
  std::vector<std::vector<uint8_t>> segments(static_cast<size_t>(h.top_plane + 1) * (levels + 1));
  for (const BitplaneSegment& s : stream.segments) {
    if (s.plane > h.top_plane || s.plane < 0 || s.level < 1 || s.level > levels + 1)
      return internal_error("encode: the bit-plane coder made a segment outside the table");
    segments[h.segment_index(s.plane, s.level - 1)] = s.bytes;
  }
  EncodedSrm out;
  out.bytes = write_srm(h, base->bytes, replay->flags, segments);
  StatusOr<SrmFile> parsed = parse_srm(out.bytes.data(), out.bytes.size());
  if (!parsed.ok()) return parsed.status().with_context("encode: re-reading its own file");
  out.header = parsed->header;
  out.header_size = parsed->header_size;
  return out;
}

namespace {

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

}  // namespace

StatusOr<DecodedSrm> decode_srm(const SrmFile& file, const SrmDecodeOptions& options) {
  const SrmHeader& h = file.header;
  int level = options.level < 0 ? h.levels : std::min(options.level, h.levels);
  uint64_t total = 0;
  for (int j = 0; j <= level; ++j) total += std::min<uint64_t>(h.level_vertices[j], options.max_vertices + 1);
  if (total > options.max_vertices)
    return invalid_argument("level " + std::to_string(level) + " has " + std::to_string(total) +
                            " vertices, over the limit of " + std::to_string(options.max_vertices));
  if (!file.base.complete()) return decode_cut_base(file);
  SRCODEC_RETURN_IF_ERROR(verify_chunk(file.base, false, "the base mesh"));
  StatusOr<DecodedBaseMesh> base = decode_base_mesh(file.base.bytes.data(), file.base.bytes.size(), grid_of(h),
                                                    h.base_vertices, h.base_triangles);
  if (!base.ok()) return base.status().with_context("base mesh at byte " + std::to_string(file.base.offset));
  if (base->positions.size() != h.base_vertices || base->triangles.size() != h.base_triangles)
    return parse_error("the base mesh has other counts than the header: the file is corrupt");
  StatusOr<TriangleHierarchy> created =
      TriangleHierarchy::create(static_cast<int32_t>(h.base_vertices), base->triangles);
  if (!created.ok()) return created.status().with_context("the base mesh is not valid");
  TriangleHierarchy& hier = created.value();
  // Every split makes 4 nodes and the midpoints of its 3 edges, each new
  // vertex the midpoint of at most 2 splits: splits <= 2/3 of the new
  // vertices, which a closed uniform hierarchy reaches. (Only a hint: `total`
  // is within the vertex limit, a corrupt count costs nothing.)
  const uint64_t new_vertices = total > h.base_vertices ? total - h.base_vertices : 0;
  hier.reserve(h.base_triangles + 4 * (2 * new_vertices / 3), total);
  // The replay runs on this thread and writes those arrays (~16 MB on the
  // bunny's 4 levels) for the first time: the other core maps their pages
  // meanwhile, which a page fault per 4 KB did here before. (Stopped on
  // return, at the latest; it only maps pages and changes no byte. Small
  // hierarchies are not worth a thread.) A header that lies about its
  // vertex counts makes this map memory the replay does not use, until the
  // replay fails and stops it; at most what `max_vertices` allows, as much as
  // a valid file of a few hundred bytes (all-split flags, no coefficients)
  // may use.
  const BackgroundPrefault prefaulting(options.threads ? hier.reserved_memory() : std::vector<MemoryRange>{},
                                       kPrefaultMinBytes);
  StatusOr<int> reached = decode_hierarchy(file, level, hier, options.max_vertices);
  if (!reached.ok()) return reached.status();
  level = reached.value();

  DecodedSrm out;
  out.level = level;
  out.base_vertices = h.base_vertices;
  out.bytes_used = file.base.offset + file.base.declared;
  for (int j = 0; j < level; ++j) out.bytes_used = file.flags[j].offset + file.flags[j].declared;
  // The wavelet plan needs only the hierarchy, the coefficients only the
  // forest: build the plan on a second thread meanwhile. Both are pure
  // functions of the hierarchy, so the result does not depend on timing.
  // The output triangles are listed by whichever thread gets to them first:
  // the plan's thread after the plan, or this one after the coefficients.
  std::atomic<bool> triangles_claimed{false};
  std::vector<std::array<int32_t, 3>> triangles;
  std::future<StatusOr<LiftingPlan>> plan_job =
      std::async(options.threads ? std::launch::async : std::launch::deferred, [&] {
    StatusOr<LiftingPlan> plan = LiftingPlan::build(hier, level);
    if (!triangles_claimed.exchange(true)) triangles = hier.level_triangles(level);
    return plan;
  });
  const ForestLayout layout = build_forest(hier, level);
  std::vector<BitplaneSegmentView> views;
  bool cut = false;
  for (int p = h.top_plane; p >= 0 && !cut; --p) {
    for (int f = 0; f <= level && !cut; ++f) {
      const size_t index = h.segment_index(p, f);
      if (index >= file.segments.size()) {  // the table ends: the encoder cut the stream here
        cut = true;
        break;
      }
      const SrmChunk& c = file.segments[index];
      SRCODEC_RETURN_IF_ERROR(verify_chunk(c, true, "segment (plane " + std::to_string(p) + ", level " +
                                                        std::to_string(f) + ")"));
      views.push_back({p, f + 1, c.bytes.data(), c.bytes.size()});
      if (!c.complete()) cut = true;
      if (!c.bytes.empty()) out.bytes_used = std::max<uint64_t>(out.bytes_used, c.offset + c.bytes.size());
    }
  }
  const std::vector<double> steps = step_table(h);
  std::vector<Eigen::Vector3d> base_positions = base->positions;
  // The forest holds every vertex of the replayed hierarchy once (its levels
  // are all <= `level`), so each detail is written below, zero or not, and
  // the array need not be cleared first (Eigen leaves it uninitialized).
  // Base vertices' slots get zeros (the lifting does not read them as details).
  std::vector<Eigen::Vector3d> detail(hier.vertex_count());
  if (layout.vertex.size() != detail.size()) std::fill(detail.begin(), detail.end(), Eigen::Vector3d::Zero());
  // Scales the values of the vertices layout.vertex[from .. to) into their
  // details, or base positions (again from the decoded base: no sum is
  // carried over if this is redone).
  const auto scale = [&](const BitplaneValueView& values, size_t from, size_t to) {
    for (size_t k = from; k < to; ++k) {
      const int32_t v = layout.vertex[k];
      const int f = hier.vertex_level(v);
      const double* step = &steps[f * kSrmComponents];
      const size_t node = k * kSrmComponents;
      Eigen::Vector3d& d = detail[v];
      for (int c = 0; c < kSrmComponents; ++c) d[c] = values.value(node + c) * step[c];
      if (f == 0) {
        base_positions[v] = base->positions[v] + d;
        d.setZero();
      }
    }
  };
  // The plan, once it is needed (the job's future gives it only once).
  std::optional<StatusOr<LiftingPlan>> plan;
  const auto take_plan = [&]() -> const StatusOr<LiftingPlan>& {
    if (!plan) plan.emplace(plan_job.get());
    return *plan;
  };
  // While the finest level's coefficients are still being decoded on the
  // other core, this thread scales the coarser levels' (which come first in
  // the forest) and runs their lifting steps: inverse lifting works level by
  // level, and the finest level's step is then all that is left. Unless the
  // decode has to start over (corrupt input only; then everything is redone).
  size_t coarse_vertices = 0;
  bool coarse_lifted = false;
  const CoarseLevelsDone coarse_done = [&](const BitplaneValueView& coarse) {
    coarse_vertices = coarse.size() / kSrmComponents;
    scale(coarse, 0, coarse_vertices);
    const StatusOr<LiftingPlan>& p = take_plan();
    if (!p.ok() || !p->covers_every_vertex(level)) return;
    inverse_lifting_in_place(p.value(), base_positions, detail, 1, level - 1, false);
    coarse_lifted = true;
  };
  BitplaneDecodeStats stats;
  StatusOr<BitplaneValues> values = decode_bitplane_values(layout.forest, h.top_plane, views, level + 1, &stats,
                                                           options.threads ? BitplaneThreads::kAuto
                                                                           : BitplaneThreads::kSequential,
                                                           h.raw_planes, coarse_done);
  if (!values.ok()) return values.status().with_context("coefficients");
  out.last_plane = stats.last_complete_plane > h.top_plane ? -1 : stats.last_complete_plane;
  const bool staged = coarse_lifted && stats.coarse_done_final;
  // The rest of the vertices (all of them unless staged); on a big mesh,
  // half of it on the other core (this also spreads the page faults of
  // `detail`).
  const size_t first = staged ? coarse_vertices : 0, vertices = layout.vertex.size();
  const BitplaneValueView all = values->view();
  run_in_halves(first, vertices, options.threads && vertices - first >= kParallelScaleVertices,
                [&](size_t begin, size_t end) { scale(all, begin, end); });
  if (!triangles_claimed.exchange(true)) triangles = hier.level_triangles(level);
  const StatusOr<LiftingPlan>& lifting = take_plan();
  if (!lifting.ok()) return lifting.status().with_context("wavelet plan");
  std::vector<Eigen::Vector3d> positions;
  if (staged) {
    inverse_lifting_in_place(lifting.value(), base_positions, detail, level, level, options.threads);
    positions = std::move(detail);
  } else {
    positions = inverse_lifting(lifting.value(), base_positions, std::move(detail), level, options.threads);
  }
  // Every vertex of the replayed hierarchy (levels <= `level`, ids 0 ..
  // vertex_count - 1) is a corner of some triangle of the level mesh: the
  // mesh is already compact (compact_mesh would copy it unchanged).
  out.mesh.positions = std::move(positions);
  out.mesh.triangles = std::move(triangles);
  return out;
}

}  // namespace srcodec
