// Base mesh coding: a cut-border traversal for connectivity (after Gumhold &
// Strasser, "Real time compression of triangle mesh connectivity", SIGGRAPH
// 1998, with Touma & Gotsman's "conquer around a focus vertex" order, GI 1998)
// and parallelogram-predicted grid positions (Touma & Gotsman §4), coded with
// the project's adaptive binary range coder (codec/range_coder.h).
//
// Connectivity. Both sides keep the cut border: the directed edges of decoded
// triangles whose other side is not known yet ("open" edges), linked into
// cycles. The current gate is an open edge (a, b); the triangle across it is
// (b, a, c), and one symbol says which vertex c is:
//   NEW       a vertex not seen yet (its position follows);
//   FORWARD   c = the end of the next border edge (closes the fan of b);
//   BACKWARD  c = the start of the previous border edge;
//   BORDER    there is no triangle across: (a, b) is on a mesh boundary;
//   OFFSET k  c = the start of the border edge k places after the next one;
//   GLOBAL i  c = vertex i, for a vertex on another border cycle (handles,
//             genus > 0) or where several fans meet.
// The new triangle's edges (a, c) and (c, b) join the border in place of the
// gate; whenever an open edge's twin is open too, the two are glued and the
// cycles re-linked (zip), which is what FORWARD/BACKWARD/close, splits and
// merges all reduce to. Gluing is decided by vertex ids alone, so OFFSET and
// GLOBAL only name c; any inconsistent stream ends in an error because every
// directed edge may be used once. When no open edge is left and triangles
// remain, a new component starts with a triangle of three (normally NEW)
// vertices. Once the triangle count is reached the remaining open edges are
// border implicitly. The gate stays on the focus vertex b until its fan
// closes (Touma-Gotsman order), so FORWARD is predicted by how many decoded
// triangles b already has: symbols are coded in the context of the triangle
// counts at b and a.
//
// Positions: each NEW vertex is predicted as a + b - o, o the third vertex of
// the gate's triangle; a component's first triangle is predicted from the
// previous vertex. Residuals are coded per coordinate (zero flag, sign,
// Elias-gamma magnitude with adaptive prefix bits).
//
// Stream: version byte, LEB128 vertex count, triangle count and payload byte
//
// This header holds what both sides share: the models, the cut border and
// the position predictions (base_mesh_encode.cpp, base_mesh_decode.cpp).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "codec/base_mesh_coder.h"
#include "codec/range_coder.h"

namespace srcodec::base_mesh_detail {

constexpr uint8_t kVersion = 1;
constexpr uint32_t kMaxCount = (1u << 28);  // vertices or triangles, far above any base mesh

using Bit = BitModel;

inline int bit_width(uint32_t x) {
  int n = 0;
  for (; x; x >>= 1) ++n;
  return n;
}

// Elias-gamma code of value + 1 with adaptive prefix (length) bits.
struct GammaModel {
  std::array<Bit, 32> prefix;
};

enum Symbol { kNew = 0, kForward, kBackward, kBorder, kOffset, kGlobal };
constexpr int kSymbolContexts = 8 * 3;
constexpr int kResidualContexts = 2;

struct Models {
  std::array<std::array<Bit, 5>, kSymbolContexts> symbol;
  Bit start_is_new;
  GammaModel offset;
  // Residuals by context: 0 after a start prediction, 1 after a parallelogram
  // (contexts by gate edge length were tried: no gain on base meshes this small).
  std::array<std::array<Bit, 3>, kResidualContexts> zero, sign;
  std::array<std::array<GammaModel, 3>, kResidualContexts> magnitude;
};

// ---------------------------------------------------------------- the cut border

inline uint64_t edge_key(int32_t from, int32_t to) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(from)) << 32) | static_cast<uint32_t>(to);
}

// An open directed edge of a decoded triangle; `opp` is that triangle's third vertex.
struct Element {
  int32_t from, to, opp;
  int32_t prev = -1, next = -1;
  bool alive = true;
};

class CutBorder {
 public:
  int32_t vertex_count() const { return static_cast<int32_t>(triangle_count_.size()); }
  int32_t new_vertex() {
    triangle_count_.push_back(0);
    return vertex_count() - 1;
  }
  int32_t triangles_at(int32_t v) const { return triangle_count_[v]; }
  const std::vector<std::array<int32_t, 3>>& triangles() const { return triangles_; }
  std::vector<std::array<int32_t, 3>> take_triangles() { return std::move(triangles_); }
  const Element& element(int32_t e) const { return elements_[e]; }

  // First triangle of a component; called only when no open edge is left.
  Status start(int32_t v0, int32_t v1, int32_t v2) {
    SRCODEC_RETURN_IF_ERROR(add_triangle_edges(v0, v1, v2));
    const int32_t e0 = make(v0, v1, v2), e1 = make(v1, v2, v0), e2 = make(v2, v0, v1);
    link(e0, e1);
    link(e1, e2);
    link(e2, e0);
    current_ = e0;
    return ok_status();
  }

  // The triangle (b, a, c) across gate (a, b).
  Status add(int32_t gate, int32_t c) {
    const int32_t a = elements_[gate].from, b = elements_[gate].to;
    SRCODEC_RETURN_IF_ERROR(add_triangle_edges(b, a, c));
    const int32_t prev = elements_[gate].prev, next = elements_[gate].next;
    kill(gate);
    const int32_t e1 = make(a, c, b), e2 = make(c, b, a);
    link(e1, e2);
    if (prev == gate) {
      link(e2, e1);
    } else {
      link(prev, e1);
      link(e2, next);
    }
    glue_to_twin(e1);
    glue_to_twin(e2);
    current_ = elements_[e2].alive ? e2 : (elements_[e1].alive ? e1 : -1);
    return ok_status();
  }

  // Gate (a, b) is a mesh boundary edge.
  void border(int32_t gate) {
    const int32_t prev = elements_[gate].prev, next = elements_[gate].next;
    kill(gate);
    if (prev == gate) {
      current_ = -1;
      return;
    }
    link(prev, next);
    current_ = next;
  }

  // The next gate, -1 when no open edge is left.
  int32_t gate() {
    if (current_ >= 0 && elements_[current_].alive) return current_;
    while (!pending_.empty()) {
      const int32_t e = pending_.back();
      pending_.pop_back();
      if (elements_[e].alive) return current_ = e;
    }
    while (scan_ < elements_.size() && !elements_[scan_].alive) ++scan_;
    return current_ = scan_ < elements_.size() ? static_cast<int32_t>(scan_) : -1;
  }

 private:
  Status add_triangle_edges(int32_t v0, int32_t v1, int32_t v2) {
    const int32_t n = vertex_count();
    for (int32_t v : {v0, v1, v2}) {
      if (v < 0 || v >= n) return parse_error("vertex " + std::to_string(v) + " does not exist yet");
    }
    if (v0 == v1 || v1 == v2 || v2 == v0) {
      return parse_error("triangle repeats vertex " + std::to_string(v0 == v1 || v0 == v2 ? v0 : v1));
    }
    const std::array<uint64_t, 3> keys = {edge_key(v0, v1), edge_key(v1, v2), edge_key(v2, v0)};
    for (uint64_t k : keys) {
      if (used_.count(k)) return parse_error("a directed edge is used twice (non-manifold connectivity)");
    }
    for (uint64_t k : keys) used_.insert(k);
    triangles_.push_back({v0, v1, v2});
    for (int32_t v : {v0, v1, v2}) ++triangle_count_[v];
    return ok_status();
  }
  int32_t make(int32_t from, int32_t to, int32_t opp) {
    elements_.push_back(Element{from, to, opp});
    const int32_t e = static_cast<int32_t>(elements_.size()) - 1;
    open_[edge_key(from, to)] = e;
    return e;
  }
  void kill(int32_t e) {
    elements_[e].alive = false;
    open_.erase(edge_key(elements_[e].from, elements_[e].to));
  }
  void link(int32_t x, int32_t y) {
    elements_[x].next = y;
    elements_[y].prev = x;
  }
  void glue_to_twin(int32_t x) {
    if (!elements_[x].alive) return;
    const auto it = open_.find(edge_key(elements_[x].to, elements_[x].from));
    if (it == open_.end()) return;
    const int32_t y = it->second;
    const int32_t xp = elements_[x].prev, xn = elements_[x].next;
    const int32_t yp = elements_[y].prev, yn = elements_[y].next;
    kill(x);
    kill(y);
    if (xn == y && yn == x) return;  // the cycle was just these two edges
    if (xn == y) {
      link(xp, yn);
    } else if (yn == x) {
      link(yp, xn);
    } else {  // a split of one cycle or the merge of two (a handle)
      link(xp, yn);
      link(yp, xn);
      pending_.push_back(yn);
      pending_.push_back(xn);
    }
  }

  std::vector<Element> elements_;
  std::unordered_map<uint64_t, int32_t> open_;  // open directed edge -> element
  std::unordered_set<uint64_t> used_;           // every decoded directed edge
  std::vector<int32_t> triangle_count_;         // per vertex
  std::vector<std::array<int32_t, 3>> triangles_;
  std::vector<int32_t> pending_;  // cycles split off, visited when the current one closes
  size_t scan_ = 0;               // elements before it are all dead
  int32_t current_ = -1;
};

inline int symbol_context(const CutBorder& cb, int32_t gate) {
  const Element& g = cb.element(gate);
  return std::min(cb.triangles_at(g.to), 7) * 3 + std::min(cb.triangles_at(g.from), 3) - 1;
}

// ---------------------------------------------------------------- positions

inline Eigen::Vector3i clamp_to_grid(const Eigen::Vector3i& v, int bits) {
  const int top = (1 << bits) - 1;
  return v.cwiseMax(0).cwiseMin(top);
}

inline Eigen::Vector3i predict_across(const std::vector<Eigen::Vector3i>& q, const Element& g, int bits) {
  return clamp_to_grid(q[g.from] + q[g.to] - q[g.opp], bits);
}

// Corner `k` of a component's first triangle; earlier corners are known.
inline Eigen::Vector3i predict_start(const std::vector<Eigen::Vector3i>& q, const std::array<int32_t, 3>& corners,
                              int k, int bits) {
  if (k == 0) return q.empty() ? Eigen::Vector3i::Constant(1 << (bits - 1)) : q.back();
  if (k == 1) return q[corners[0]];
  return clamp_to_grid((q[corners[0]] + q[corners[1]]) / 2, bits);
}

inline Status check_grid(const QuantizationGrid& grid) {
  if (!(grid.step > 0) || !std::isfinite(grid.step) || !grid.origin.allFinite()) {
    return invalid_argument("quantization grid: step must be finite and > 0, origin finite");
  }
  if (grid.bits < 1 || grid.bits > 24) {
    return invalid_argument("quantization grid: bits " + std::to_string(grid.bits) + " not in 1..24");
  }
  return ok_status();
}

}  // namespace srcodec::base_mesh_detail
