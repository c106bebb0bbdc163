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
#include "wavelet/butterfly_stencil.h"

#include <algorithm>
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

// The corner of the triangle across a wing edge; -1 on the boundary.
int32_t across(const LevelMesh& mesh, const WingEdge& e) { return mesh.third(e.v, e.u); }

// Wing of the 8-point stencil across edge e: the corner across, or the
// reflection u + v - w when the edge is on the boundary.
void wing(const LevelMesh& mesh, const WingEdge& e, std::vector<Tap>* out) {
  constexpr double kWing = -1.0 / 16;
  const int32_t corner = across(mesh, e);
  if (corner >= 0) {
    add(out, corner, kWing);
    return;
  }
  add(out, e.u, kWing);
  add(out, e.v, kWing);
  add(out, e.w, -kWing);
}

// Triangles (a, b, x) and (b, a, y).
void eight_point(const LevelMesh& mesh, int32_t a, int32_t b, int32_t x, int32_t y, std::vector<Tap>* out) {
  add(out, a, 0.5);
  add(out, b, 0.5);
  add(out, x, 1.0 / 8);
  add(out, y, 1.0 / 8);
  for (const WingEdge& e : wing_edges(a, b, x, y)) wing(mesh, e, out);
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
bool eight_point_rule(const LevelMesh& mesh, int32_t a, int32_t b) {
  const int32_t va = mesh.valence(a), vb = mesh.valence(b);
  const bool ba = mesh.on_boundary(a), bb = mesh.on_boundary(b);
  return (va == 6 && vb == 6) || (ba && vb == 6) || (bb && va == 6) || (ba && bb);
}

void interior_taps(const LevelMesh& mesh, int32_t a, int32_t b, int32_t x, int32_t y, std::vector<Tap>* out) {
  if (eight_point_rule(mesh, a, b)) {
    eight_point(mesh, a, b, x, y, out);
    return;
  }
  const int32_t va = mesh.valence(a), vb = mesh.valence(b);
  const bool ba = mesh.on_boundary(a), bb = mesh.on_boundary(b);
  const bool irregular_a = va != 6 && !ba, irregular_b = vb != 6 && !bb;
  const double scale = (irregular_a && irregular_b) ? 0.5 : 1.0;
  if (irregular_a) extraordinary(mesh, a, b, scale, out);
  if (irregular_b) extraordinary(mesh, b, a, scale, out);
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

std::array<int32_t, 4> regular_wings(const LevelMesh& mesh, int32_t a, int32_t b, int32_t left, int32_t right) {
  const std::array<int32_t, 4> none{-1, -1, -1, -1};
  if (left < 0 || right < 0 || !eight_point_rule(mesh, a, b)) return none;
  std::array<int32_t, 4> w = none;
  const std::array<WingEdge, 4> edges = wing_edges(a, b, left, right);
  for (int k = 0; k < 4; ++k)
    if ((w[k] = across(mesh, edges[k])) < 0) return none;
  return w;
}

void butterfly_taps(const LevelMesh& mesh, int32_t a, int32_t b, int32_t left, int32_t right,
                    std::vector<Tap>* taps) {
  const size_t from = taps->size();
  const bool forward = left >= 0, backward = right >= 0;
  if (forward && backward)
    interior_taps(mesh, a, b, left, right, taps);
  else if (forward)
    four_point(mesh, a, b, taps);
  else
    four_point(mesh, b, a, taps);
  merge(taps, from);
}

}  // namespace srcodec
