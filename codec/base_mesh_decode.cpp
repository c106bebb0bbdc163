// The decoding half of the base mesh coder (codec/base_mesh_model.h has the
// scheme).
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/base_mesh_coder.h"
#include "codec/base_mesh_model.h"
#include "codec/range_coder.h"

namespace srcodec {

using namespace base_mesh_detail;

namespace {

// False when the length exceeds `max_length` bits (corrupt stream).
bool decode_gamma(ArithmeticDecoder& dec, GammaModel& m, int max_length, uint32_t* value) {
  int n = 0;
  while (dec.decode(m.prefix[n])) {
    if (++n > max_length) return false;
  }
  *value = ((1u << n) | dec.decode_raw(n)) - 1;
  return true;
}

Symbol decode_symbol(ArithmeticDecoder& dec, std::array<Bit, 5>& m) {
  for (int i = 0; i < 4; ++i) {
    if (dec.decode(m[i])) return static_cast<Symbol>(i);
  }
  return dec.decode(m[4]) ? kOffset : kGlobal;
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

// ---------------------------------------------------------------- stream header

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
