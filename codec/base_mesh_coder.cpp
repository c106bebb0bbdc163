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
// count, then the arithmetic-coded payload (exactly that many bytes).
#include "codec/base_mesh_coder.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "codec/range_coder.h"

namespace srcodec {
namespace {

constexpr uint8_t kVersion = 1;
constexpr uint32_t kMaxCount = (1u << 28);  // vertices or triangles, far above any base mesh

// ---------------------------------------------------------------- entropy coding
// The adaptive binary range coder of codec/range_coder.h.

using Bit = BitModel;

int bit_width(uint32_t x) {
  int n = 0;
  for (; x; x >>= 1) ++n;
  return n;
}

// Elias-gamma code of value + 1 with adaptive prefix (length) bits.
struct GammaModel {
  std::array<Bit, 32> prefix;
};

void encode_gamma(ArithmeticEncoder& enc, GammaModel& m, uint32_t value) {
  const uint32_t x = value + 1;
  const int n = bit_width(x) - 1;
  for (int i = 0; i < n; ++i) enc.encode(1, m.prefix[i]);
  enc.encode(0, m.prefix[n]);
  enc.encode_raw(x - (1u << n), n);
}

// False when the length exceeds `max_length` bits (corrupt stream).
bool decode_gamma(ArithmeticDecoder& dec, GammaModel& m, int max_length, uint32_t* value) {
  int n = 0;
  while (dec.decode(m.prefix[n])) {
    if (++n > max_length) return false;
  }
  *value = ((1u << n) | dec.decode_raw(n)) - 1;
  return true;
}

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

void encode_symbol(ArithmeticEncoder& enc, std::array<Bit, 5>& m, Symbol s) {
  for (int i = 0; i < 4; ++i) {
    enc.encode(s == i, m[i]);
    if (s == i) return;
  }
  enc.encode(s == kOffset, m[4]);
}

Symbol decode_symbol(ArithmeticDecoder& dec, std::array<Bit, 5>& m) {
  for (int i = 0; i < 4; ++i) {
    if (dec.decode(m[i])) return static_cast<Symbol>(i);
  }
  return dec.decode(m[4]) ? kOffset : kGlobal;
}

void encode_residual(ArithmeticEncoder& enc, Models& m, int context, const Eigen::Vector3i& r) {
  for (int j = 0; j < 3; ++j) {
    enc.encode(r[j] == 0, m.zero[context][j]);
    if (r[j] == 0) continue;
    enc.encode(r[j] < 0, m.sign[context][j]);
    encode_gamma(enc, m.magnitude[context][j], static_cast<uint32_t>(std::abs(r[j])) - 1);
  }
}

bool decode_residual(ArithmeticDecoder& dec, Models& m, int context, int bits, Eigen::Vector3i* r) {
  for (int j = 0; j < 3; ++j) {
    (*r)[j] = 0;
    if (dec.decode(m.zero[context][j])) continue;
    const bool negative = dec.decode(m.sign[context][j]);
    uint32_t magnitude = 0;
    if (!decode_gamma(dec, m.magnitude[context][j], bits, &magnitude)) return false;
    if (magnitude >= (1u << bits)) return false;  // |residual| <= 2^bits - 1
    (*r)[j] = negative ? -static_cast<int>(magnitude + 1) : static_cast<int>(magnitude + 1);
  }
  return true;
}

// ---------------------------------------------------------------- the cut border

uint64_t edge_key(int32_t from, int32_t to) {
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

int symbol_context(const CutBorder& cb, int32_t gate) {
  const Element& g = cb.element(gate);
  return std::min(cb.triangles_at(g.to), 7) * 3 + std::min(cb.triangles_at(g.from), 3) - 1;
}

// ---------------------------------------------------------------- positions

Eigen::Vector3i clamp_to_grid(const Eigen::Vector3i& v, int bits) {
  const int top = (1 << bits) - 1;
  return v.cwiseMax(0).cwiseMin(top);
}

Eigen::Vector3i predict_across(const std::vector<Eigen::Vector3i>& q, const Element& g, int bits) {
  return clamp_to_grid(q[g.from] + q[g.to] - q[g.opp], bits);
}

// Corner `k` of a component's first triangle; earlier corners are known.
Eigen::Vector3i predict_start(const std::vector<Eigen::Vector3i>& q, const std::array<int32_t, 3>& corners,
                              int k, int bits) {
  if (k == 0) return q.empty() ? Eigen::Vector3i::Constant(1 << (bits - 1)) : q.back();
  if (k == 1) return q[corners[0]];
  return clamp_to_grid((q[corners[0]] + q[corners[1]]) / 2, bits);
}

Status check_grid(const QuantizationGrid& grid) {
  if (!(grid.step > 0) || !std::isfinite(grid.step) || !grid.origin.allFinite()) {
    return invalid_argument("quantization grid: step must be finite and > 0, origin finite");
  }
  if (grid.bits < 1 || grid.bits > 24) {
    return invalid_argument("quantization grid: bits " + std::to_string(grid.bits) + " not in 1..24");
  }
  return ok_status();
}

// ---------------------------------------------------------------- stream header

void write_varint(std::vector<uint8_t>& out, uint32_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v));
}

Status read_varint(const uint8_t* data, size_t size, size_t* pos, const char* what, uint32_t* v) {
  *v = 0;
  for (int shift = 0; shift < 35; shift += 7) {
    if (*pos >= size) {
      return parse_error(std::string("base mesh: stream ends inside the ") + what + " at byte offset " +
                         std::to_string(*pos));
    }
    const uint8_t b = data[(*pos)++];
    *v |= static_cast<uint32_t>(b & 0x7F) << shift;
    if (!(b & 0x80)) {
      if (*v > kMaxCount) break;
      return ok_status();
    }
  }
  return parse_error(std::string("base mesh: ") + what + " too large at byte offset " + std::to_string(*pos));
}

}  // namespace

Eigen::Vector3d QuantizationGrid::dequantize(const Eigen::Vector3i& q) const {
  return origin + step * q.cast<double>();
}

Eigen::Vector3i QuantizationGrid::quantize(const Eigen::Vector3d& p) const {
  const double top = std::ldexp(1.0, std::clamp(bits, 1, 30)) - 1.0;
  Eigen::Vector3i q;
  for (int j = 0; j < 3; ++j) {
    const double x = std::floor((p[j] - origin[j]) / step + 0.5);
    q[j] = std::isnan(x) ? 0 : static_cast<int>(std::clamp(x, 0.0, top));
  }
  return q;
}

namespace {

// ---------------------------------------------------------------- encoder

using EdgeMap = std::unordered_map<uint64_t, int32_t>;  // input directed edge -> 3 * triangle + corner

StatusOr<EdgeMap> validate_input(const std::vector<Eigen::Vector3d>& positions,
                                 const std::vector<std::array<int32_t, 3>>& triangles) {
  if (triangles.empty()) return invalid_mesh("base mesh: no triangles");
  if (positions.size() > kMaxCount || triangles.size() > kMaxCount) {
    return invalid_mesh("base mesh: too many vertices or triangles");
  }
  const int32_t n = static_cast<int32_t>(positions.size());
  for (int32_t v = 0; v < n; ++v) {
    if (!positions[v].allFinite()) return invalid_mesh("base mesh: vertex " + std::to_string(v) + " is not finite");
  }
  EdgeMap edges;
  edges.reserve(triangles.size() * 3);
  std::vector<bool> used(positions.size(), false);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    const std::string where = "base mesh: triangle " + std::to_string(t);
    for (int32_t v : tri) {
      if (v < 0 || v >= n) return invalid_mesh(where + " has vertex index " + std::to_string(v) + " out of range");
      used[v] = true;
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) return invalid_mesh(where + " repeats a vertex");
    for (int i = 0; i < 3; ++i) {
      const auto inserted = edges.emplace(edge_key(tri[i], tri[(i + 1) % 3]), static_cast<int32_t>(3 * t + i));
      if (!inserted.second) {
        return invalid_mesh(where + " uses directed edge (" + std::to_string(tri[i]) + ", " +
                            std::to_string(tri[(i + 1) % 3]) + ") already used by triangle " +
                            std::to_string(inserted.first->second / 3) +
                            ": a non-manifold edge or an inconsistently oriented (flipped) triangle");
      }
    }
  }
  for (int32_t v = 0; v < n; ++v) {
    if (!used[v]) return invalid_mesh("base mesh: vertex " + std::to_string(v) + " is used by no triangle");
  }
  return edges;
}

class Encoder {
 public:
  Encoder(const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<int32_t, 3>>& triangles,
          const QuantizationGrid& grid, EdgeMap edges)
      : triangles_(triangles), grid_(grid), edges_(std::move(edges)),
        new_id_(positions.size(), -1), coded_(triangles.size(), false) {
    old_q_.reserve(positions.size());
    for (const auto& p : positions) old_q_.push_back(grid.quantize(p));
  }

  BaseMeshCode run() {
    size_t coded = 0;
    while (coded < triangles_.size()) {
      const int32_t gate = cb_.gate();
      if (gate < 0) {
        start_component();
        ++coded;
        continue;
      }
      const Element& g = cb_.element(gate);
      const auto it = edges_.find(edge_key(out_.new_to_old_vertex[g.to], out_.new_to_old_vertex[g.from]));
      std::array<Bit, 5>& model = models_.symbol[symbol_context(cb_, gate)];
      if (it == edges_.end()) {
        encode_symbol(enc_, model, kBorder);
        cb_.border(gate);
        continue;
      }
      const int32_t t = it->second / 3;
      const int32_t old_c = triangles_[t][(it->second + 2) % 3];
      coded_[t] = true;
      ++coded;
      out_.new_to_old_triangle.push_back(t);
      int32_t c = new_id_[old_c];
      if (c < 0) {
        encode_symbol(enc_, model, kNew);
        c = add_vertex(old_c, predict_across(q_, g, grid_.bits), 1);
      } else {
        encode_existing(gate, c, model);
      }
      const Status s = cb_.add(gate, c);
      (void)s;  // cannot fail on validated input; the final decode check would catch it
    }
    return finish();
  }

 private:
  void start_component() {
    while (coded_[next_start_]) ++next_start_;
    const auto& tri = triangles_[next_start_];
    coded_[next_start_] = true;
    out_.new_to_old_triangle.push_back(static_cast<int32_t>(next_start_));
    std::array<int32_t, 3> corners{};
    for (int k = 0; k < 3; ++k) {
      const bool is_new = new_id_[tri[k]] < 0;
      enc_.encode(is_new, models_.start_is_new);
      if (is_new) {
        corners[k] = add_vertex(tri[k], predict_start(q_, corners, k, grid_.bits), 0);
      } else {
        corners[k] = new_id_[tri[k]];
        encode_global(corners[k]);
      }
    }
    const Status s = cb_.start(corners[0], corners[1], corners[2]);
    (void)s;
  }

  int32_t add_vertex(int32_t old_v, const Eigen::Vector3i& prediction, int context) {
    const int32_t v = cb_.new_vertex();
    new_id_[old_v] = v;
    out_.new_to_old_vertex.push_back(old_v);
    q_.push_back(old_q_[old_v]);
    encode_residual(enc_, models_, context, old_q_[old_v] - prediction);
    return v;
  }

  void encode_global(int32_t v) { enc_.encode_raw(static_cast<uint32_t>(v), bit_width(cb_.vertex_count() - 1)); }

  void encode_existing(int32_t gate, int32_t c, std::array<Bit, 5>& model) {
    const Element& g = cb_.element(gate);
    if (cb_.element(g.next).to == c) return encode_symbol(enc_, model, kForward);
    if (cb_.element(g.prev).from == c) return encode_symbol(enc_, model, kBackward);
    uint32_t k = 1;
    for (int32_t e = cb_.element(g.next).next; e != gate; e = cb_.element(e).next, ++k) {
      if (cb_.element(e).from == c) {
        encode_symbol(enc_, model, kOffset);
        encode_gamma(enc_, models_.offset, k - 1);
        return;
      }
    }
    encode_symbol(enc_, model, kGlobal);
    encode_global(c);
  }

  BaseMeshCode finish() {
    std::vector<uint8_t> payload = enc_.finish();
    out_.bytes.push_back(kVersion);
    write_varint(out_.bytes, static_cast<uint32_t>(q_.size()));
    write_varint(out_.bytes, static_cast<uint32_t>(triangles_.size()));
    write_varint(out_.bytes, static_cast<uint32_t>(payload.size()));
    out_.bytes.insert(out_.bytes.end(), payload.begin(), payload.end());
    out_.triangles = cb_.take_triangles();
    for (const auto& q : q_) out_.positions.push_back(grid_.dequantize(q));
    return std::move(out_);
  }

  const std::vector<std::array<int32_t, 3>>& triangles_;
  const QuantizationGrid& grid_;
  EdgeMap edges_;
  std::vector<Eigen::Vector3i> old_q_;  // per input vertex
  std::vector<Eigen::Vector3i> q_;      // per new vertex
  std::vector<int32_t> new_id_;
  std::vector<bool> coded_;
  size_t next_start_ = 0;
  CutBorder cb_;
  Models models_;
  ArithmeticEncoder enc_;
  BaseMeshCode out_;
};

// ---------------------------------------------------------------- decoder

class Decoder {
 public:
  Decoder(const uint8_t* payload, size_t size, size_t header_size, const QuantizationGrid& grid,
          uint32_t vertex_count, uint32_t triangle_count)
      : dec_(payload, size), header_size_(header_size), grid_(grid),
        vertex_count_(vertex_count), triangle_count_(triangle_count) {}

  // `prefix`: the payload may be cut; the result is then the triangles (and
  // their vertices) decoded before the first symbol that depended on a
  // missing byte. Vertices are numbered in the step that first uses them, so
  // the first t triangles use exactly the first v vertices.
  StatusOr<DecodedBaseMesh> run(bool prefix) {
    size_t good_triangles = 0;
    size_t good_vertices = 0;
    while (cb_.triangles().size() < triangle_count_) {
      const int32_t gate = cb_.gate();
      const Status s = gate < 0 ? start_component() : decode_gate(gate);
      if (prefix && !dec_.ok()) return first(good_triangles, good_vertices);
      if (!s.ok()) return error(s.message());
      if (!dec_.ok()) return error("the payload ends early");
      good_triangles = cb_.triangles().size();
      good_vertices = q_.size();
    }
    if (cb_.vertex_count() != static_cast<int32_t>(vertex_count_)) {
      return error("decoded " + std::to_string(cb_.vertex_count()) + " vertices, the header says " +
                   std::to_string(vertex_count_));
    }
    if (!dec_.ok()) return error("the payload ends early");
    return first(cb_.triangles().size(), q_.size());
  }

 private:
  DecodedBaseMesh first(size_t triangles, size_t vertices) {
    DecodedBaseMesh mesh;
    mesh.triangles = cb_.take_triangles();
    mesh.triangles.resize(triangles);
    mesh.positions.reserve(vertices);
    for (size_t v = 0; v < vertices; ++v) mesh.positions.push_back(grid_.dequantize(q_[v]));
    return mesh;
  }

  Status error(const std::string& what) const {
    return parse_error("base mesh: " + what + " at byte offset " +
                       std::to_string(header_size_ + dec_.bytes_consumed()));
  }

  Status start_component() {
    std::array<int32_t, 3> corners{};
    for (int k = 0; k < 3; ++k) {
      if (dec_.decode(models_.start_is_new)) {
        SRCODEC_ASSIGN_OR_RETURN(corners[k], add_vertex(predict_start(q_, corners, k, grid_.bits), 0));
      } else {
        SRCODEC_ASSIGN_OR_RETURN(corners[k], decode_global());
      }
    }
    return cb_.start(corners[0], corners[1], corners[2]);
  }

  Status decode_gate(int32_t gate) {
    const Element g = cb_.element(gate);
    const Symbol symbol = decode_symbol(dec_, models_.symbol[symbol_context(cb_, gate)]);
    int32_t c = -1;
    switch (symbol) {
      case kBorder:
        cb_.border(gate);
        return ok_status();
      case kNew: {
        SRCODEC_ASSIGN_OR_RETURN(c, add_vertex(predict_across(q_, g, grid_.bits), 1));
        break;
      }
      case kForward:
        c = cb_.element(g.next).to;
        break;
      case kBackward:
        c = cb_.element(g.prev).from;
        break;
      case kOffset: {
        uint32_t k = 0;
        if (!decode_gamma(dec_, models_.offset, 30, &k)) return parse_error("border offset too long");
        int32_t e = cb_.element(g.next).next;
        for (uint32_t i = 0; i < k && e != gate; ++i) e = cb_.element(e).next;
        if (e == gate) return parse_error("border offset " + std::to_string(k + 1) + " beyond the border cycle");
        c = cb_.element(e).from;
        break;
      }
      case kGlobal: {
        SRCODEC_ASSIGN_OR_RETURN(c, decode_global());
        break;
      }
    }
    return cb_.add(gate, c);
  }

  StatusOr<int32_t> add_vertex(const Eigen::Vector3i& prediction, int context) {
    if (cb_.vertex_count() >= static_cast<int32_t>(vertex_count_)) {
      return parse_error("more vertices than the header's " + std::to_string(vertex_count_));
    }
    Eigen::Vector3i r;
    if (!decode_residual(dec_, models_, context, grid_.bits, &r)) return parse_error("position residual too large");
    const Eigen::Vector3i q = prediction + r;
    if (q != clamp_to_grid(q, grid_.bits)) return parse_error("position outside the quantization grid");
    q_.push_back(q);
    return cb_.new_vertex();
  }

  StatusOr<int32_t> decode_global() {
    const int32_t n = cb_.vertex_count();
    if (n == 0) return parse_error("reference to a vertex before any vertex");
    const uint32_t v = dec_.decode_raw(bit_width(static_cast<uint32_t>(n - 1)));
    if (v >= static_cast<uint32_t>(n)) return parse_error("reference to vertex " + std::to_string(v) + " not yet decoded");
    return static_cast<int32_t>(v);
  }

  ArithmeticDecoder dec_;
  size_t header_size_;
  const QuantizationGrid& grid_;
  uint32_t vertex_count_, triangle_count_;
  CutBorder cb_;
  Models models_;
  std::vector<Eigen::Vector3i> q_;
};

}  // namespace

StatusOr<BaseMeshCode> encode_base_mesh(const std::vector<Eigen::Vector3d>& positions,
                                        const std::vector<std::array<int32_t, 3>>& triangles,
                                        const QuantizationGrid& grid) {
  SRCODEC_RETURN_IF_ERROR(check_grid(grid));
  SRCODEC_ASSIGN_OR_RETURN(EdgeMap edges, validate_input(positions, triangles));
  BaseMeshCode code = Encoder(positions, triangles, grid, std::move(edges)).run();
  // The decoder is cheap on base meshes: prove that it rebuilds exactly what the encoder promises.
  const auto decoded = decode_base_mesh(code.bytes.data(), code.bytes.size(), grid, positions.size(),
                                        triangles.size());
  if (!decoded.ok()) return internal_error("base mesh encoder: own stream does not decode: " + decoded.status().message());
  if (decoded->triangles != code.triangles || decoded->positions != code.positions) {
    return internal_error("base mesh encoder: decoded mesh differs from the encoder's");
  }
  return code;
}

namespace {

StatusOr<DecodedBaseMesh> decode(const uint8_t* data, size_t size, const QuantizationGrid& grid,
                                 size_t max_vertices, size_t max_triangles, bool prefix) {
  SRCODEC_RETURN_IF_ERROR(check_grid(grid));
  if (data == nullptr && size > 0) return invalid_argument("base mesh: no data");
  if (prefix) {
    // Nothing decodes before the version byte and the three counts (varints)
    // are all there.
    size_t pos = 1;
    for (int k = 0; k < 3 && pos <= size; ++k) {
      while (pos < size && (data[pos] & 0x80)) ++pos;
      ++pos;  // past the varint's last byte
    }
    if (size < 1 || pos > size) return DecodedBaseMesh{};
  }
  if (size < 1) return parse_error("base mesh: empty stream at byte offset 0");
  if (data[0] != kVersion) {
    return parse_error("base mesh: unsupported version " + std::to_string(data[0]) + " at byte offset 0");
  }
  size_t pos = 1;
  uint32_t vertices = 0, triangles = 0, payload = 0;
  SRCODEC_RETURN_IF_ERROR(read_varint(data, size, &pos, "vertex count", &vertices));
  SRCODEC_RETURN_IF_ERROR(read_varint(data, size, &pos, "triangle count", &triangles));
  SRCODEC_RETURN_IF_ERROR(read_varint(data, size, &pos, "payload size", &payload));
  const std::string at = " at byte offset " + std::to_string(pos);
  if (vertices > max_vertices || triangles > max_triangles) {
    return parse_error("base mesh: " + std::to_string(vertices) + " vertices, " + std::to_string(triangles) +
                       " triangles exceed the limits " + std::to_string(max_vertices) + ", " +
                       std::to_string(max_triangles) + at);
  }
  if (triangles == 0 || vertices < 3 || vertices > 3ull * triangles) {
    return parse_error("base mesh: " + std::to_string(vertices) + " vertices cannot be used by " +
                       std::to_string(triangles) + " triangles" + at);
  }
  if (prefix ? payload < size - pos : payload != size - pos) {
    return parse_error("base mesh: payload of " + std::to_string(payload) + " bytes declared, " +
                       std::to_string(size - pos) + " present" + at);
  }
  return Decoder(data + pos, size - pos, pos, grid, vertices, triangles).run(prefix);
}

}  // namespace

StatusOr<DecodedBaseMesh> decode_base_mesh(const uint8_t* data, size_t size, const QuantizationGrid& grid,
                                           size_t max_vertices, size_t max_triangles) {
  return decode(data, size, grid, max_vertices, max_triangles, false);
}

StatusOr<DecodedBaseMesh> decode_base_mesh_prefix(const uint8_t* data, size_t size, const QuantizationGrid& grid,
                                                  size_t max_vertices, size_t max_triangles) {
  return decode(data, size, grid, max_vertices, max_triangles, true);
}

}  // namespace srcodec
