// The encoding half of the base mesh coder (codec/base_mesh_model.h has the
// scheme).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "codec/base_mesh_coder.h"
#include "codec/base_mesh_model.h"
#include "codec/range_coder.h"

namespace srcodec {

using namespace base_mesh_detail;

namespace {

void encode_gamma(ArithmeticEncoder& enc, GammaModel& m, uint32_t value) {
  const uint32_t x = value + 1;
  const int n = bit_width(x) - 1;
  for (int i = 0; i < n; ++i) enc.encode(1, m.prefix[i]);
  enc.encode(0, m.prefix[n]);
  enc.encode_raw(x - (1u << n), n);
}

void encode_symbol(ArithmeticEncoder& enc, std::array<Bit, 5>& m, Symbol s) {
  for (int i = 0; i < 4; ++i) {
    enc.encode(s == i, m[i]);
    if (s == i) return;
  }
  enc.encode(s == kOffset, m[4]);
}

void encode_residual(ArithmeticEncoder& enc, Models& m, int context, const Eigen::Vector3i& r) {
  for (int j = 0; j < 3; ++j) {
    enc.encode(r[j] == 0, m.zero[context][j]);
    if (r[j] == 0) continue;
    enc.encode(r[j] < 0, m.sign[context][j]);
    encode_gamma(enc, m.magnitude[context][j], static_cast<uint32_t>(std::abs(r[j])) - 1);
  }
}

// ---------------------------------------------------------------- stream header

void write_varint(std::vector<uint8_t>& out, uint32_t v) {
  while (v >= 0x80) {
    out.push_back(static_cast<uint8_t>(v | 0x80));
    v >>= 7;
  }
  out.push_back(static_cast<uint8_t>(v));
}

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

}  // namespace srcodec
