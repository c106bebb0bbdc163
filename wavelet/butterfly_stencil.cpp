// Modified Butterfly stencils (Zorin, Schröder, Sweldens 1996, §4), written to
// give the same weights as OpenMesh's Subdivider::Uniform::ModifiedButterflyT
// wherever that is defined:
//  - boundary edge: 4-point rule -1/16, 9/16, 9/16, -1/16 along the boundary;
//  - interior edge whose ends are both valence 6, or one boundary end and the
//    other valence 6, or both ends on the boundary: the 8-point stencil
//    1/2, 1/2, 1/8, 1/8, -1/16 x 4; a wing vertex missing because its edge is
//    on the boundary is replaced by the reflection of the opposite corner
//    across that edge's midpoint (u + v - w);
//  - otherwise each interior end of valence K != 6 gives the extraordinary
//    rule 3/4 on itself and s_i on its ring (s_i = (1/4 + cos(2 pi i/K) +
//    1/2 cos(4 pi i/K)) / K for K >= 5; K = 3: 5/12, -1/12, -1/12; K = 4: 3/8,
//    0, -1/8, 0), and the stencil is the average over those ends.
// See wavelet/README.md for why this is the rule at the boundary.
// With creases (README, "Creases"), the same rules on the mesh cut open
// along them, and the 4-point rule along each crease curve (Hoppe et al.
// 1994; Biermann, Levin, Zorin 2000).
#include "wavelet/butterfly_stencil.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace srcodec {
namespace {

using Tap = LiftingPlan::Tap;
constexpr double kPi = 3.14159265358979323846;

// Appends a tap, writing its two fields (not a 16-byte temporary built on the
// stack and copied: two narrow stores read back as one wide load cannot be
// forwarded, which stalled every push_back of the plan build).
void add(std::vector<Tap>* out, int32_t vertex, double weight) {
  Tap& t = out->emplace_back();
  t.vertex = vertex;
  t.weight = weight;
}

// Steps bounded by the vertex's valence: a walk that does not end in a
// manifold fan gives up instead of looping.
int32_t walk_limit(const LevelMesh& mesh, int32_t v) { return mesh.valence(v) + 2; }

// Boundary neighbour of q reached by turning around q from the triangle that
// holds the directed edge (p, q), away from p; -1 if the fan does not end.
int32_t boundary_neighbour_after(const LevelMesh& mesh, int32_t p, int32_t q) {
  int32_t r = mesh.third(p, q);  // triangle (p, q, r): q's outgoing edge (q, r)
  for (int32_t step = 0; r >= 0 && step < walk_limit(mesh, q); ++step) {
    const int32_t s = mesh.third(r, q);  // triangle (r, q, s) across (q, r)
    if (s < 0) return r;
    r = s;
  }
  return -1;
}

// Boundary neighbour of p reached by turning around p from the triangle that
// holds the directed edge (p, q), away from q; -1 if the fan does not end.
int32_t boundary_neighbour_before(const LevelMesh& mesh, int32_t p, int32_t q) {
  int32_t r = mesh.third(p, q);  // triangle (p, q, r): p's incoming edge (r, p)
  for (int32_t step = 0; r >= 0 && step < walk_limit(mesh, p); ++step) {
    const int32_t s = mesh.third(p, r);  // triangle (p, r, s) across (r, p)
    if (s < 0) return r;
    r = s;
  }
  return -1;
}

void four_point(const LevelMesh& mesh, int32_t p, int32_t q, std::vector<Tap>* out) {
  const int32_t before = boundary_neighbour_before(mesh, p, q);
  const int32_t after = boundary_neighbour_after(mesh, p, q);
  if (before < 0 || after < 0) {  // not a manifold boundary: linear
    add(out, p, 0.5);
    add(out, q, 0.5);
    return;
  }
  add(out, p, 9.0 / 16);
  add(out, q, 9.0 / 16);
  add(out, before, -1.0 / 16);
  add(out, after, -1.0 / 16);
}

// The edge (u, v) of a triangle (u, v, w) (directed edge (u, v) in it)
// across which an 8-point stencil has a wing.
struct WingEdge {
  int32_t u, v, w;
};

// The four wing edges of the 8-point stencil on (a, b), triangles (a, b, x)
// and (b, a, y), in the order of LiftingPlan::Odd::wing.
std::array<WingEdge, 4> wing_edges(int32_t a, int32_t b, int32_t x, int32_t y) {
  return {{{b, x, a}, {x, a, b}, {a, y, b}, {y, b, a}}};
}

// The mesh as the interior rules see it. `Whole`: the level mesh itself.
// `CutOpen`: the level mesh cut open along its creases, each side of a
// crease a surface with that crease as its boundary (Hoppe et al. 1994,
// Biermann, Levin, Zorin 2000): nothing lies across a crease edge, and a
// crease vertex is a boundary vertex. A vertex that is not a crease vertex
// keeps its valence and its closed or open fan, so the rules' valence tests
// and fan walks (extraordinary, four_point) need no cut: they are only
// asked about such vertices.
struct Whole {
  const LevelMesh& mesh;
  // The corner of the triangle across a wing edge; -1 on the boundary.
  int32_t across(const WingEdge& e) const { return mesh.third(e.v, e.u); }
  bool on_boundary(int32_t v) const { return mesh.on_boundary(v); }
};

struct CutOpen {
  const LevelMesh& mesh;
  const SharpEdges& sharp;
  int32_t across(const WingEdge& e) const { return sharp.crease(e.u, e.v) ? -1 : mesh.third(e.v, e.u); }
  bool on_boundary(int32_t v) const { return mesh.on_boundary(v) || sharp.crease_vertex(v); }
};

// Wing of the 8-point stencil across edge e: the corner across, or the
// reflection u + v - w when the edge is on the boundary.
template <typename Surface>
void wing(const Surface& surface, const WingEdge& e, std::vector<Tap>* out) {
  constexpr double kWing = -1.0 / 16;
  const int32_t corner = surface.across(e);
  if (corner >= 0) {
    add(out, corner, kWing);
    return;
  }
  add(out, e.u, kWing);
  add(out, e.v, kWing);
  add(out, e.w, -kWing);
}

// Triangles (a, b, x) and (b, a, y).
template <typename Surface>
void eight_point(const Surface& surface, int32_t a, int32_t b, int32_t x, int32_t y, std::vector<Tap>* out) {
  add(out, a, 0.5);
  add(out, b, 0.5);
  add(out, x, 1.0 / 8);
  add(out, y, 1.0 / 8);
  for (const WingEdge& e : wing_edges(a, b, x, y)) wing(surface, e, out);
}

// A scratch array of n values on the stack, or on the heap when n exceeds
// what a stencil normally has.
template <typename T>
class StackFirst {
 public:
  explicit StackFirst(size_t n) : data_(local_) {
    if (n > kLocal) {
      heap_.resize(n);
      data_ = heap_.data();
    }
  }
  StackFirst(const StackFirst&) = delete;
  StackFirst& operator=(const StackFirst&) = delete;
  T& operator[](size_t i) { return data_[i]; }

 private:
  static constexpr size_t kLocal = 64;
  T local_[kLocal];
  std::vector<T> heap_;
  T* data_;
};

double extraordinary_weight_uncached(int32_t k, int32_t i) {
  if (k == 3) return i == 0 ? 5.0 / 12 : -1.0 / 12;
  if (k == 4) return i == 0 ? 3.0 / 8 : (i == 2 ? -1.0 / 8 : 0.0);
  const double inv_k = 1.0 / k;
  return (0.25 + std::cos(2.0 * kPi * i * inv_k) + 0.5 * std::cos(4.0 * kPi * i * inv_k)) * inv_k;
}

// The weights of valences up to kCachedValence, worked out once by the same
// function (so the same doubles): two cosines per tap are a noticeable share
// of the plan build (docs/codec_design.md).
constexpr int32_t kCachedValence = 16;
struct WeightTable {
  double w[kCachedValence + 1][kCachedValence];
};

double extraordinary_weight(int32_t k, int32_t i) {
  static const WeightTable table = [] {
    WeightTable t{};
    for (int32_t kk = 3; kk <= kCachedValence; ++kk)
      for (int32_t ii = 0; ii < kk; ++ii) t.w[kk][ii] = extraordinary_weight_uncached(kk, ii);
    return t;
  }();
  return k <= kCachedValence ? table.w[k][i] : extraordinary_weight_uncached(k, i);
}

// The K-valence rule of interior vertex e for its edge to o, scaled by
// `scale`: the ring from o on, turning through the triangles (e, v_i, v_i+1).
void extraordinary(const LevelMesh& mesh, int32_t e, int32_t o, double scale, std::vector<Tap>* out) {
  // The ring on the stack (a heap vector cost a malloc and free per call).
  const int32_t limit = walk_limit(mesh, e);
  StackFirst<int32_t> ring(static_cast<size_t>(limit) + 1);
  int32_t size = 0;
  ring[size++] = o;
  bool closed = false;
  for (int32_t step = 0; step < limit && !closed; ++step) {
    const int32_t next = mesh.third(e, ring[size - 1]);
    if (next < 0) break;
    closed = next == o;
    if (!closed) ring[size++] = next;
  }
  if (!closed) size = 0;  // not a closed fan after all
  const int32_t k = size;
  if (k < 3) {  // no Butterfly rule for such a fan: linear
    add(out, e, 0.5 * scale);
    add(out, o, 0.5 * scale);
    return;
  }
  double sum = 0.0;
  for (int32_t i = 0; i < k; ++i) {
    const double w = extraordinary_weight(k, i);
    sum += w;
    add(out, ring[i], w * scale);
  }
  add(out, e, (1.0 - sum) * scale);  // 3/4, as OpenMesh computes it
}

// Whether the interior edge (a, b) takes the 8-point rule.
template <typename Surface>
bool eight_point_rule(const Surface& surface, int32_t a, int32_t b) {
  const int32_t va = surface.mesh.valence(a), vb = surface.mesh.valence(b);
  const bool ba = surface.on_boundary(a), bb = surface.on_boundary(b);
  return (va == 6 && vb == 6) || (ba && vb == 6) || (bb && va == 6) || (ba && bb);
}

template <typename Surface>
void interior_taps(const Surface& surface, int32_t a, int32_t b, int32_t x, int32_t y, std::vector<Tap>* out) {
  if (eight_point_rule(surface, a, b)) {
    eight_point(surface, a, b, x, y, out);
    return;
  }
  const int32_t va = surface.mesh.valence(a), vb = surface.mesh.valence(b);
  const bool ba = surface.on_boundary(a), bb = surface.on_boundary(b);
  const bool irregular_a = va != 6 && !ba, irregular_b = vb != 6 && !bb;
  const double scale = (irregular_a && irregular_b) ? 0.5 : 1.0;
  if (irregular_a) extraordinary(surface.mesh, a, b, scale, out);
  if (irregular_b) extraordinary(surface.mesh, b, a, scale, out);
}

// The 4-point rule along the sharp curve through the sharp edge (p, q)
// (the 4-point scheme of Dyn, Levin, Gregory 1987, the modified Butterfly's
// boundary rule: Zorin, Schröder, Sweldens 1996): -1/16, 9/16, 9/16, -1/16.
// Where the curve ends at p (a corner, a dart, or the end of an open curve)
// the point before p is the ghost 2p - q, the linear extrapolation, so p's
// weight becomes 7/16 and q's 10/16: a straight curve stays straight and a
// corner stays sharp (Hoppe et al. 1994 likewise subdivide each crease
// curve on its own between corners). Both ends ending: the midpoint. The
// sums of these dyadic weights are exact.
void curve(const SharpEdges& sharp, int32_t p, int32_t q, std::vector<Tap>* out) {
  add(out, p, 9.0 / 16);
  add(out, q, 9.0 / 16);
  for (const auto& [end, other] : {std::array<int32_t, 2>{p, q}, std::array<int32_t, 2>{q, p}}) {
    const int32_t next = sharp.curve_neighbour(end, other);
    if (next >= 0) {
      add(out, next, -1.0 / 16);
    } else {  // -1/16 (2 end - other)
      add(out, end, -2.0 / 16);
      add(out, other, 1.0 / 16);
    }
  }
}

// Sorts by vertex, stably (the weights of a repeated vertex are summed in the
// order they were appended), sums the weights of repeated vertices, drops
// zeros. The sort is an insertion sort (a stencil has a few dozen taps at
// most) of 64-bit keys, the vertex (sign bit flipped: signed order) above the
// tap's position, so that equal vertices keep their order and each move is
// one register-sized copy.
void merge(std::vector<Tap>* taps, size_t from) {
  constexpr uint32_t kSign = 0x80000000u;
  std::vector<Tap>& t = *taps;
  const size_t count = t.size() - from;
  StackFirst<uint64_t> keys(count);
  for (size_t i = 0; i < count; ++i) {
    const uint64_t key = (static_cast<uint64_t>(static_cast<uint32_t>(t[from + i].vertex) ^ kSign) << 32) | i;
    size_t k = i;
    for (; k > 0 && keys[k - 1] > key; --k) keys[k] = keys[k - 1];
    keys[k] = key;
  }
  // Weights by position, then the merged taps written over the range.
  StackFirst<double> weights(count);
  for (size_t i = 0; i < count; ++i) weights[i] = t[from + i].weight;
  size_t write = from;
  for (size_t i = 0; i < count;) {
    const uint32_t vertex = static_cast<uint32_t>(keys[i] >> 32);
    double sum = weights[static_cast<uint32_t>(keys[i])];
    for (++i; i < count && static_cast<uint32_t>(keys[i] >> 32) == vertex; ++i)
      sum += weights[static_cast<uint32_t>(keys[i])];
    if (sum != 0.0) {
      t[write].vertex = static_cast<int32_t>(vertex ^ kSign);
      t[write].weight = sum;
      ++write;
    }
  }
  t.resize(write);
}

}  // namespace

StatusOr<LevelMesh> LevelMesh::build(const std::vector<std::array<int32_t, 3>>& triangles, int32_t vertex_count) {
  LevelMesh m;
  m.begin_.assign(static_cast<size_t>(vertex_count) + 1, 0);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int c = 0; c < 3; ++c) {
      const int32_t v = triangles[t][c];
      if (v < 0 || v >= vertex_count)
        return internal_error("level mesh triangle " + std::to_string(t) + " has corner " + std::to_string(v) +
                              " out of range");
      ++m.begin_[v + 1];
    }
  for (int32_t v = 0; v < vertex_count; ++v) m.begin_[v + 1] += m.begin_[v];
  m.out_.resize(3 * triangles.size());
  std::vector<uint32_t> fill(m.begin_.begin(), m.begin_.end() - 1);
  for (const auto& t : triangles)
    for (int c = 0; c < 3; ++c) {
      m.out_[fill[t[c]]++] = {t[(c + 1) % 3], t[(c + 2) % 3]};
    }
  m.valence_.assign(vertex_count, 0);
  m.boundary_.assign(vertex_count, 0);
  for (int32_t a = 0; a < vertex_count; ++a) {
    m.valence_[a] += static_cast<int32_t>(m.begin_[a + 1] - m.begin_[a]);
    for (uint32_t i = m.begin_[a]; i < m.begin_[a + 1]; ++i) {
      const int32_t b = m.out_[i].to;
      for (uint32_t k = i + 1; k < m.begin_[a + 1]; ++k)
        if (m.out_[k].to == b)
          return invalid_mesh("level mesh uses the directed edge (" + std::to_string(a) + ", " +
                              std::to_string(b) + ") twice (not manifold)");
      if (m.third(b, a) >= 0) continue;
      m.boundary_[a] = m.boundary_[b] = 1;
      ++m.valence_[b];  // b's neighbour a has no edge b -> a
    }
  }
  return m;
}

std::vector<std::array<int32_t, 2>> LevelMesh::boundary_edges() const {
  std::vector<std::array<int32_t, 2>> out;
  for (int32_t a = 0; a < vertex_count(); ++a)
    for (uint32_t i = begin_[a]; i < begin_[a + 1]; ++i)
      if (third(out_[i].to, a) < 0) out.push_back({a, out_[i].to});
  return out;
}

StatusOr<SharpEdges> SharpEdges::build(const LevelMesh& mesh, const std::vector<std::array<int32_t, 2>>& creases) {
  const int32_t n = mesh.vertex_count();
  // Every sharp edge once as (min, max, crease?), creases first where an
  // edge is both, then grouped by vertex by counting sort.
  struct Sharp {
    int32_t a, b;
    bool crease;
  };
  std::vector<Sharp> all;
  for (const auto& [a, b] : creases) {
    if (a < 0 || b < 0 || a >= n || b >= n || !mesh.has_edge(a, b))
      return internal_error("lifting: crease (" + std::to_string(a) + ", " + std::to_string(b) +
                            ") is not an edge of its level mesh");
    all.push_back({std::min(a, b), std::max(a, b), true});
  }
  for (const auto& [a, b] : mesh.boundary_edges()) all.push_back({std::min(a, b), std::max(a, b), false});
  std::sort(all.begin(), all.end(), [](const Sharp& x, const Sharp& y) {
    return x.a != y.a ? x.a < y.a : (x.b != y.b ? x.b < y.b : x.crease > y.crease);
  });
  const auto same_edge = [](const Sharp& x, const Sharp& y) { return x.a == y.a && x.b == y.b; };
  all.erase(std::unique(all.begin(), all.end(), same_edge), all.end());
  SharpEdges s;
  s.begin_.assign(static_cast<size_t>(n) + 1, 0);
  s.crease_vertex_.assign(n, 0);
  for (const Sharp& e : all) {
    ++s.begin_[e.a + 1];
    ++s.begin_[e.b + 1];
    if (e.crease) s.crease_vertex_[e.a] = s.crease_vertex_[e.b] = 1;
  }
  for (int32_t v = 0; v < n; ++v) s.begin_[v + 1] += s.begin_[v];
  s.edges_.resize(2 * all.size());
  std::vector<uint32_t> fill(s.begin_.begin(), s.begin_.end() - 1);
  for (const Sharp& e : all) {
    s.edges_[fill[e.a]++] = {e.b, e.crease};
    s.edges_[fill[e.b]++] = {e.a, e.crease};
  }
  return s;
}

namespace {

template <typename Surface>
std::array<int32_t, 4> wings_of(const Surface& surface, int32_t a, int32_t b, int32_t left, int32_t right) {
  const std::array<int32_t, 4> none{-1, -1, -1, -1};
  if (left < 0 || right < 0 || !eight_point_rule(surface, a, b)) return none;
  std::array<int32_t, 4> w = none;
  const std::array<WingEdge, 4> edges = wing_edges(a, b, left, right);
  for (int k = 0; k < 4; ++k)
    if ((w[k] = surface.across(edges[k])) < 0) return none;
  return w;
}

}  // namespace

std::array<int32_t, 4> regular_wings(const LevelMesh& mesh, int32_t a, int32_t b, int32_t left, int32_t right) {
  return wings_of(Whole{mesh}, a, b, left, right);
}

std::array<int32_t, 4> regular_wings(const LevelMesh& mesh, const SharpEdges& sharp, int32_t a, int32_t b,
                                     int32_t left, int32_t right) {
  if (sharp.crease(a, b)) return {-1, -1, -1, -1};
  return wings_of(CutOpen{mesh, sharp}, a, b, left, right);
}

void butterfly_taps(const LevelMesh& mesh, int32_t a, int32_t b, int32_t left, int32_t right,
                    std::vector<Tap>* taps) {
  const size_t from = taps->size();
  const bool forward = left >= 0, backward = right >= 0;
  if (forward && backward)
    interior_taps(Whole{mesh}, a, b, left, right, taps);
  else if (forward)
    four_point(mesh, a, b, taps);
  else
    four_point(mesh, b, a, taps);
  merge(taps, from);
}

void butterfly_taps(const LevelMesh& mesh, const SharpEdges& sharp, int32_t a, int32_t b, int32_t left,
                    int32_t right, std::vector<Tap>* taps) {
  const size_t from = taps->size();
  const bool forward = left >= 0, backward = right >= 0;
  if (forward && backward && !sharp.crease(a, b))
    interior_taps(CutOpen{mesh, sharp}, a, b, left, right, taps);
  else if ((forward && backward) || sharp.crease_vertex(a) || sharp.crease_vertex(b))
    curve(sharp, a, b, taps);
  else if (forward)  // a boundary edge between two vertices off the creases: the rule without creases
    four_point(mesh, a, b, taps);
  else
    four_point(mesh, b, a, taps);
  merge(taps, from);
}

uint32_t update_divisor(const LevelMesh& mesh, const SharpEdges& sharp, int32_t v, int32_t w) {
  if (!sharp.crease_vertex(v)) return static_cast<uint32_t>(mesh.valence(v));
  return sharp.degree(v) == 2 && sharp.sharp(v, w) ? kCurveUpdateDivisor : 0;
}

}  // namespace srcodec
