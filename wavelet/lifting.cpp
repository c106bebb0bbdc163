// Lifted Butterfly wavelet transform (Schröder, Sweldens, "Spherical
// Wavelets", SIGGRAPH 1995, §3 lifting; Zorin, Schröder, Sweldens 1996 for the
// predict stencil; local frames as in Khodakovsky, Schröder, Sweldens,
// "Progressive Geometry Compression", SIGGRAPH 2000, §3.2). Level j:
//   predict  d_v = x_v - sum_i w_i x_i          (v odd, i even, stencil taps)
//   update   x_a += u_a d_v, x_b += u_b d_v     (parent edge (a, b))
//   frame    d_v -> (n, t, s) of the updated level-(j-1) mesh around (a, b)
// Along creases the stencils and update weights follow curve rules
// (wavelet/README.md, "Creases").
// Inverse: the same steps undone in reverse order, levels 1 .. L.
#include "wavelet/lifting.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include <Eigen/Geometry>

#include "format/in_halves.h"
#include "format/semi_regular/creases.h"
#include "wavelet/butterfly_stencil.h"

namespace srcodec {
namespace {

using Eigen::Vector3d;

// Levels with at least this many odd vertices run their frame and predict
// steps on two threads in inverse_lifting (a thread costs tens of microseconds).
constexpr std::ptrdiff_t kParallelOdds = 16384;

// Relative size below which a normal or tangent counts as degenerate.
constexpr double kDegenerate = 1e-12;

// The unit vector perpendicular to `v` (unit or not, nonzero) made with the
// coordinate axis along which v is smallest: deterministic, never NaN.
Vector3d perpendicular(const Vector3d& v) {
  Vector3d axis = Vector3d::Zero();
  Eigen::Index i = 0;
  v.cwiseAbs().minCoeff(&i);
  axis[i] = 1.0;
  const Vector3d p = v.cross(axis);
  const double len = p.norm();
  return len > 0.0 ? Vector3d(p / len) : Vector3d(1.0, 0.0, 0.0);
}

struct Frame {
  Vector3d n, t, s;  // normal, tangent along the parent edge, n x t
};

// Frame of the odd vertex on edge (a, b): n = sum of the area-weighted
// normals of the triangles (a, b, l) and (b, a, r) present; t = (b - a)
// projected off n. Degenerate pieces fall back to deterministic axes.
Frame edge_frame(const Vector3d& a, const Vector3d& b, const Vector3d* left, const Vector3d* right) {
  const Vector3d e = b - a;
  Vector3d n = Vector3d::Zero();
  double scale = e.squaredNorm();
  if (left) {
    n += e.cross(*left - a);
    scale += (*left - a).squaredNorm();
  }
  if (right) {
    n += (-e).cross(*right - b);
    scale += (*right - b).squaredNorm();
  }
  Frame f;
  const double n_len = n.norm();
  const double e_len = e.norm();
  if (n_len > kDegenerate * scale)
    f.n = n / n_len;
  else if (e_len > 0.0)
    f.n = perpendicular(e);
  else
    f.n = Vector3d(0.0, 0.0, 1.0);
  const Vector3d t = e - e.dot(f.n) * f.n;
  const double t_len = t.norm();
  f.t = t_len > kDegenerate * e_len ? Vector3d(t / t_len) : perpendicular(f.n);
  f.s = f.n.cross(f.t);
  return f;
}

Frame odd_frame(const LiftingPlan::Odd& o, const std::vector<Vector3d>& x) {
  return edge_frame(x[o.a], x[o.b], o.left >= 0 ? &x[o.left] : nullptr, o.right >= 0 ? &x[o.right] : nullptr);
}

Vector3d predict(const LiftingPlan::Odd& o, const LiftingPlan::Tap* taps, const std::vector<Vector3d>& x) {
  if (o.regular())
    return 0.5 * (x[o.a] + x[o.b]) + 0.125 * (x[o.left] + x[o.right]) -
           0.0625 * ((x[o.wing[0]] + x[o.wing[1]]) + (x[o.wing[2]] + x[o.wing[3]]));
  Vector3d p = Vector3d::Zero();
  for (uint32_t i = o.taps_begin(); i < o.taps_end(); ++i) p += taps[i].weight * x[taps[i].vertex];
  return p;
}

// The odd vertices of levels 1 .. max_level, level by level, each level in
// increasing id order (ids are not sorted by level in adaptive hierarchies).
std::vector<int32_t> odd_vertices_by_level(const TriangleHierarchy& h, int32_t max_level,
                                           std::vector<uint32_t>* level_begin) {
  level_begin->assign(static_cast<size_t>(max_level) + 1, 0);
  const int32_t nv = h.vertex_count();
  for (int32_t v = h.base_vertex_count(); v < nv; ++v) {
    const int32_t l = h.vertex_level(v);
    if (l >= 1 && l <= max_level) ++(*level_begin)[l];
  }
  for (int32_t l = 1; l <= max_level; ++l) (*level_begin)[l] += (*level_begin)[l - 1];
  std::vector<uint32_t> fill(level_begin->begin(), level_begin->end() - 1);
  std::vector<int32_t> out((*level_begin)[max_level]);
  for (int32_t v = h.base_vertex_count(); v < nv; ++v) {
    const int32_t l = h.vertex_level(v);
    if (l >= 1 && l <= max_level) out[fill[l - 1]++] = v;
  }
  return out;
}

using Edges = std::vector<std::array<int32_t, 2>>;

std::string edge_text(const std::array<int32_t, 2>& e) {
  return "(" + std::to_string(e[0]) + ", " + std::to_string(e[1]) + ")";
}

// LiftingPlan::build's contract on the base creases: each an edge of the
// base mesh as (a, b) with a < b, the list sorted with no repeats.
Status check_base_creases(const TriangleHierarchy& h, const Edges& creases) {
  if (creases.empty()) return ok_status();
  const int32_t n = h.base_vertex_count();
  for (size_t i = 0; i < creases.size(); ++i) {
    const auto [a, b] = creases[i];
    const std::string which = "lifting: crease " + edge_text(creases[i]) + " (entry " + std::to_string(i) + ")";
    if (a >= b) return invalid_argument(which + " is not written with a < b");
    if (a < 0 || b >= n)
      return invalid_argument(which + " is not an edge of the base mesh: its vertices are not both base vertices, "
                              "below " + std::to_string(n));
    if (i > 0 && !(creases[i - 1] < creases[i]))
      return invalid_argument(which + " comes after " + edge_text(creases[i - 1]) +
                              ": crease edges are not sorted, with no repeats");
  }
  SRCODEC_ASSIGN_OR_RETURN(const LevelMesh base, LevelMesh::build(h.level_triangles(0), n));
  for (const auto& e : creases)
    if (!base.has_edge(e[0], e[1]))
      return invalid_argument("lifting: crease " + edge_text(e) + " is not an edge of the base mesh");
  return ok_status();
}

// The rules of one level mesh as the plan build asks for them: the plain
// Butterfly's, or with creases (README, "Creases").
struct PlainRules {
  const LevelMesh& mesh;
  uint32_t update_divisor(int32_t v, int32_t) const { return static_cast<uint32_t>(mesh.valence(v)); }
  std::array<int32_t, 4> wings(int32_t a, int32_t b, int32_t left, int32_t right) const {
    return regular_wings(mesh, a, b, left, right);
  }
  void taps(int32_t a, int32_t b, int32_t left, int32_t right, std::vector<LiftingPlan::Tap>* out) const {
    butterfly_taps(mesh, a, b, left, right, out);
  }
};

struct CreaseRules {
  const LevelMesh& mesh;
  const SharpEdges& sharp;
  uint32_t update_divisor(int32_t v, int32_t w) const { return srcodec::update_divisor(mesh, sharp, v, w); }
  std::array<int32_t, 4> wings(int32_t a, int32_t b, int32_t left, int32_t right) const {
    return regular_wings(mesh, sharp, a, b, left, right);
  }
  void taps(int32_t a, int32_t b, int32_t left, int32_t right, std::vector<LiftingPlan::Tap>* out) const {
    butterfly_taps(mesh, sharp, a, b, left, right, out);
  }
};

// Appends the records of level j's `count` odd vertices `odd` (increasing
// id), whose parent edges are edges of rules.mesh, the level-(j-1) mesh of
// `mesh_vertices` vertices. Forced inline into LiftingPlan::build, where the
// level mesh is a const object the stencil calls cannot change; as a call of
// its own, the loop reloads the mesh's arrays after each stencil call (1.4%
// more instructions in the plan build, callgrind).
template <typename Rules>
[[gnu::always_inline]] inline Status add_odds(const Rules& rules, int32_t mesh_vertices,
                                              const TriangleHierarchy& hierarchy, const int32_t* odd, uint32_t count,
                                              int32_t j, std::vector<LiftingPlan::Odd>* odds,
                                              std::vector<LiftingPlan::Tap>* taps) {
  const LevelMesh& mesh = rules.mesh;
  for (uint32_t k = 0; k < count; ++k) {
    // Filled in place (the reserved array does not move): an Odd built on
    // the stack field by field and then copied is read back with wide loads
    // from narrow stores, which the CPU cannot forward.
    LiftingPlan::Odd& o = odds->emplace_back();
    o.v = odd[k];
    const auto edge = hierarchy.parent_edge(o.v);
    o.a = edge[0];
    o.b = edge[1];
    if (o.a >= 0 && o.b >= 0 && o.a < mesh_vertices && o.b < mesh_vertices) {
      o.left = mesh.third(o.a, o.b);
      o.right = mesh.third(o.b, o.a);
    }
    if (o.left < 0 && o.right < 0)
      return internal_error("lifting: parent edge (" + std::to_string(o.a) + ", " + std::to_string(o.b) +
                            ") of vertex " + std::to_string(o.v) + " is not an edge of the level-" +
                            std::to_string(j - 1) + " mesh");
    o.update_divisor_a = rules.update_divisor(o.a, o.b);
    o.update_divisor_b = rules.update_divisor(o.b, o.a);
    o.wing = rules.wings(o.a, o.b, o.left, o.right);
    if (!o.regular()) {
      const size_t taps_begin = taps->size();
      rules.taps(o.a, o.b, o.left, o.right, taps);
      if (taps->size() > static_cast<size_t>(INT32_MAX)) return invalid_argument("lifting: over 2^31 stencil taps");
      o.wing[1] = static_cast<int32_t>(taps_begin);
      o.wing[2] = static_cast<int32_t>(taps->size());
    }
  }
  return ok_status();
}

}  // namespace

const LiftingPlan::Odd* LiftingPlan::odd_begin(int32_t level) const {
  if (level < 1 || level > built_levels_) return odds_.data();
  return odds_.data() + level_begin_[level - 1];
}

const LiftingPlan::Odd* LiftingPlan::odd_end(int32_t level) const {
  if (level < 1 || level > built_levels_) return odds_.data();
  return odds_.data() + level_begin_[level];
}

StatusOr<LiftingPlan> LiftingPlan::build(const TriangleHierarchy& hierarchy, int32_t levels,
                                         const std::vector<std::array<int32_t, 2>>& base_creases) {
  if (levels < 0) return invalid_argument("lifting: levels must be >= 0, got " + std::to_string(levels));
  SRCODEC_RETURN_IF_ERROR(check_base_creases(hierarchy, base_creases));
  Edges creases = base_creases;  // of the level-(j-1) mesh
  LiftingPlan plan;
  plan.levels_ = levels;
  plan.built_levels_ = std::min(levels, hierarchy.max_level());
  plan.base_vertex_count_ = hierarchy.base_vertex_count();
  plan.vertex_count_ = hierarchy.vertex_count();
  const std::vector<int32_t> odd = odd_vertices_by_level(hierarchy, plan.built_levels_, &plan.level_begin_);
  plan.odds_.reserve(odd.size());
  for (int32_t j = 1; j <= plan.built_levels_; ++j) {
    const uint32_t first = plan.level_begin_[j - 1], last = plan.level_begin_[j];
    if (first == last) continue;
    // The level mesh spans the ids up to its largest corner, not every vertex
    // of the hierarchy: level by level (the decoder's replay) the coarse
    // levels' ids come first, and their meshes stay small.
    const std::vector<std::array<int32_t, 3>> triangles = hierarchy.level_triangles(j - 1);
    int32_t mesh_vertices = 0;
    for (const auto& t : triangles) mesh_vertices = std::max({mesh_vertices, t[0] + 1, t[1] + 1, t[2] + 1});
    SRCODEC_ASSIGN_OR_RETURN(const LevelMesh mesh, LevelMesh::build(triangles, mesh_vertices));
    // Levels without creases take the plain rules, untouched (and as fast:
    // the rules are a template parameter, not a test per odd vertex).
    const int32_t* level_odd = odd.data() + first;
    const uint32_t count = last - first;
    Status added;
    if (creases.empty()) {
      added = add_odds(PlainRules{mesh}, mesh_vertices, hierarchy, level_odd, count, j, &plan.odds_, &plan.taps_);
    } else {
      SRCODEC_ASSIGN_OR_RETURN(const SharpEdges sharp, SharpEdges::build(mesh, creases));
      const CreaseRules rules{mesh, sharp};
      added = add_odds(rules, mesh_vertices, hierarchy, level_odd, count, j, &plan.odds_, &plan.taps_);
    }
    SRCODEC_RETURN_IF_ERROR(added);
    if (!creases.empty()) creases = refined_crease_edges(creases, hierarchy, odd.data() + first, odd.data() + last);
  }
  return plan;
}

bool LiftingPlan::covers_every_vertex(int32_t level) const {
  size_t covered = static_cast<size_t>(base_vertex_count_);
  for (int32_t j = 1; j <= level; ++j) covered += static_cast<size_t>(odd_end(j) - odd_begin(j));
  return covered == static_cast<size_t>(vertex_count_);
}

std::vector<LiftingPlan::Tap> LiftingPlan::stencil(const Odd& o) const {
  if (!o.regular()) return {taps_.begin() + o.taps_begin(), taps_.begin() + o.taps_end()};
  return {{o.a, 0.5},          {o.b, 0.5},          {o.left, 0.125},     {o.right, 0.125},
          {o.wing[0], -0.0625}, {o.wing[1], -0.0625}, {o.wing[2], -0.0625}, {o.wing[3], -0.0625}};
}

WaveletCoefficients forward_lifting(const LiftingPlan& plan, const std::vector<Vector3d>& positions) {
  const size_t nv = static_cast<size_t>(plan.vertex_count());
  std::vector<Vector3d> x(nv, Vector3d::Zero());
  std::copy_n(positions.begin(), std::min(nv, positions.size()), x.begin());
  WaveletCoefficients out;
  out.detail.assign(nv, Vector3d::Zero());
  const LiftingPlan::Tap* taps = plan.taps().data();
  for (int32_t j = plan.levels(); j >= 1; --j) {
    const LiftingPlan::Odd* begin = plan.odd_begin(j);
    const LiftingPlan::Odd* end = plan.odd_end(j);
    for (const auto* o = begin; o != end; ++o) out.detail[o->v] = x[o->v] - predict(*o, taps, x);
    for (const auto* o = begin; o != end; ++o) {
      const Vector3d& d = out.detail[o->v];
      x[o->a] += o->update_a() * d;
      x[o->b] += o->update_b() * d;
    }
    for (const auto* o = begin; o != end; ++o) {
      const Frame f = odd_frame(*o, x);
      Vector3d& d = out.detail[o->v];
      d = Vector3d(f.n.dot(d), f.t.dot(d), f.s.dot(d));
    }
  }
  out.base.assign(x.begin(), x.begin() + plan.base_vertex_count());
  return out;
}

namespace {

// Level j's step of the inverse transform on `x` (positions of levels < j),
// reading each odd vertex's detail from `details` (which may be `x` itself:
// each odd slot is read, as its detail, before anything writes it).
void inverse_level(const LiftingPlan& plan, int32_t j, std::vector<Vector3d>& x, const std::vector<Vector3d>& details,
                   bool threads) {
  const LiftingPlan::Tap* taps = plan.taps().data();
  const LiftingPlan::Odd* begin = plan.odd_begin(j);
  const LiftingPlan::Odd* end = plan.odd_end(j);
  // The world-space detail waits in the odd vertex's own slot (still zero,
  // or its detail when in place, and read by no stencil or frame of this
  // level) until the predict step. A zero detail needs no frame and moves
  // nothing.
  // The frame and predict steps touch each odd vertex's own slot only (and
  // read even ones): on a big level, half of each runs on a second thread.
  // The update step scatters to shared even vertices and stays serial.
  const auto to_world = [&](const LiftingPlan::Odd* from, const LiftingPlan::Odd* to) {
    for (const auto* o = from; o != to; ++o) {
      if (static_cast<size_t>(o->v) >= details.size()) continue;
      const Vector3d d = details[o->v];  // a copy: in place, x[o->v] is written below
      if (d.x() == 0.0 && d.y() == 0.0 && d.z() == 0.0) continue;
      const Frame f = odd_frame(*o, x);
      x[o->v] = d.x() * f.n + d.y() * f.t + d.z() * f.s;
    }
  };
  const auto add_prediction = [&](const LiftingPlan::Odd* from, const LiftingPlan::Odd* to) {
    for (const auto* o = from; o != to; ++o) x[o->v] += predict(*o, taps, x);
  };
  // Runs step over [begin, end), the second half on another thread when
  // the level is big.
  const bool two_threads = threads && end - begin >= kParallelOdds;
  const auto in_halves = [begin, end, two_threads](const auto& step) { run_in_halves(begin, end, two_threads, step); };
  in_halves(to_world);
  for (const auto* o = begin; o != end; ++o) {
    const Vector3d d = x[o->v];
    if (d.x() == 0.0 && d.y() == 0.0 && d.z() == 0.0) continue;
    x[o->a] -= o->update_a() * d;
    x[o->b] -= o->update_b() * d;
  }
  in_halves(add_prediction);
}

}  // namespace

std::vector<Vector3d> inverse_lifting(const LiftingPlan& plan, const std::vector<Vector3d>& base,
                                      std::vector<Vector3d> detail, int32_t level, bool threads) {
  const size_t nv = static_cast<size_t>(plan.vertex_count());
  level = std::clamp(level, 0, plan.levels());
  // The positions are worked out in place of the details when every vertex
  // is a base vertex or an odd one of levels 1 .. level (each odd slot is
  // read, as its detail, before anything else writes it): one array of the
  // finest mesh's size less to allocate. Otherwise in a zeroed copy.
  const bool in_place = detail.size() == nv && plan.covers_every_vertex(level);
  std::vector<Vector3d> x;
  if (in_place) {
    x = std::move(detail);
    detail.clear();
    inverse_lifting_in_place(plan, base, x, 1, level, threads);
    return x;
  }
  x.assign(nv, Vector3d::Zero());
  std::copy_n(base.begin(), std::min({nv, base.size(), static_cast<size_t>(plan.base_vertex_count())}), x.begin());
  for (int32_t j = 1; j <= level; ++j) inverse_level(plan, j, x, detail, threads);
  return x;
}

void inverse_lifting_in_place(const LiftingPlan& plan, const std::vector<Vector3d>& base, std::vector<Vector3d>& x,
                              int32_t first, int32_t last, bool threads) {
  assert(x.size() == static_cast<size_t>(plan.vertex_count()));
  last = std::min(last, plan.levels());
  if (first <= 1) {
    const size_t base_count = std::min(x.size(), static_cast<size_t>(plan.base_vertex_count()));
    std::fill_n(x.begin(), base_count, Vector3d::Zero());
    std::copy_n(base.begin(), std::min(base.size(), base_count), x.begin());
    first = 1;
  }
  for (int32_t j = first; j <= last; ++j) inverse_level(plan, j, x, x, threads);
}

}  // namespace srcodec
