// The encoding half of the .srm codec (codec/srm_codec.h): transform,
// quantize and code a semi-regular mesh.
#include <algorithm>
#include <cmath>
#include <string>

#include "codec/base_mesh_coder.h"
#include "codec/bitplane.h"
#include "codec/crease_coder.h"
#include "codec/flags_coder.h"
#include "codec/srm_codec.h"
#include "codec/srm_layout.h"
#include "wavelet/lifting.h"

namespace srcodec {
namespace {

constexpr int32_t kMaxQuantized = (1 << kSrmMaxPlane) - 1;

// What the header stores as f32, rounded the same way on both sides.
double as_float(double v) { return static_cast<double>(static_cast<float>(v)); }

double component(const Eigen::Vector3d& v, int c) { return v[c]; }

// The creases in the base mesh coder's vertex ids (the file's and the
// decoder's), sorted again.
std::vector<std::array<int32_t, 2>> renumbered(const std::vector<std::array<int32_t, 2>>& creases,
                                               const std::vector<int32_t>& new_to_old_vertex) {
  std::vector<int32_t> old_to_new(new_to_old_vertex.size(), -1);
  for (size_t v = 0; v < new_to_old_vertex.size(); ++v) old_to_new[new_to_old_vertex[v]] = static_cast<int32_t>(v);
  std::vector<std::array<int32_t, 2>> out;
  for (const auto& e : creases) {
    const int32_t a = old_to_new[e[0]], b = old_to_new[e[1]];
    out.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(out.begin(), out.end());
  return out;
}

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
  // The plan's build also checks the creases (base edges, a < b, sorted).
  StatusOr<LiftingPlan> original_plan = LiftingPlan::build(mesh.hierarchy, levels, mesh.crease_edges);
  if (!original_plan.ok()) return original_plan.status().with_context("encode: wavelet plan");
  const std::vector<Eigen::Vector3d> approximation = forward_lifting(original_plan.value(), mesh.positions).base;
  StatusOr<BaseMeshCode> base = encode_base_mesh(approximation, mesh.base.triangles, grid_of(h));
  if (!base.ok()) return base.status().with_context("encode: base mesh");
  StatusOr<ReplayedHierarchy> replay = encode_refinement(mesh.hierarchy, levels, base->triangles,
                                                         base->new_to_old_vertex, base->new_to_old_triangle);
  if (!replay.ok()) return replay.status().with_context("encode");
  const TriangleHierarchy& hier = replay->hierarchy;
  // Without creases there is no crease chunk: the file is version 1 or 2.
  const std::vector<std::array<int32_t, 2>> creases = renumbered(mesh.crease_edges, base->new_to_old_vertex);
  std::vector<uint8_t> crease_bytes;
  if (!creases.empty()) {
    StatusOr<std::vector<uint8_t>> coded = encode_creases(base->triangles, creases);
    if (!coded.ok()) return coded.status().with_context("encode");
    crease_bytes = std::move(coded.value());
  }
  h.has_creases = !creases.empty();
  h.base_vertices = nbase;
  h.base_triangles = base->triangles.size();
  h.level_vertices.assign(levels + 1, 0);
  for (int32_t v = 0; v < hier.vertex_count(); ++v) ++h.level_vertices[hier.vertex_level(v)];

  std::vector<Eigen::Vector3d> positions(hier.vertex_count());
  for (int32_t v = 0; v < hier.vertex_count(); ++v) positions[v] = mesh.positions[replay->to_original_vertex[v]];
  StatusOr<LiftingPlan> plan = LiftingPlan::build(hier, levels, creases);
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
  out.bytes = write_srm(h, base->bytes, replay->flags, segments, crease_bytes);
  StatusOr<SrmFile> parsed = parse_srm(out.bytes.data(), out.bytes.size());
  if (!parsed.ok()) return parsed.status().with_context("encode: re-reading its own file");
  out.header = parsed->header;
  out.header_size = parsed->header_size;
  return out;
}

}  // namespace srcodec
